// Emitting glsl nodes' translated code.
#include "codegen/glsl_code.hpp"

#include "glsl/opencl_packets.hpp"
#include "glsl/opencl_translation.hpp"

#include <fmt/format.h>

#include <set>
#include <string_view>

namespace clmarch {
namespace {

void collect_programs(const Node& node, std::vector<const GlslProgram*>& programs, std::set<std::string>& names) {
  if (node.kind == NodeKind::Glsl) {
    const GlslProgram* program = params_of<Glsl>(node).program.get();
    if (names.insert(program->name).second) programs.push_back(program);
  }
  for (const Node& child : node.children) collect_programs(child, programs, names);
}

// Packets of LANES points call the packet translation where the user's code has one
// (glsl/opencl_packets.hpp); otherwise, as code that branches or loops per point must, they run
// one lane at a time through private arrays (OpenCL C has no run-time index of a vector's lanes).
// One point per work-item (GPUs) calls the scalar translation.
std::string lane_wrappers(const GlslProgram& program, std::string_view vector3, bool packets) {
  const std::string& name = program.name;
  const char* distance_lanes =
      "  real x[LANES], y[LANES], z[LANES], d[LANES];\n"
      "  VSTORE_LANES(p.x, 0, x);\n"
      "  VSTORE_LANES(p.y, 0, y);\n"
      "  VSTORE_LANES(p.z, 0, z);\n"
      "  for (int lane = 0; lane < LANES; ++lane) d[lane] = {0}_distance(({1})(x[lane], y[lane], z[lane]), t);\n"
      "  return VLOAD_LANES(0, d);\n";
  std::string code = fmt::format(
      "/* The user's distance on each lane of a packet. */\n"
      "vfloat {0}_distance_lanes(vec3v p, real t) {{\n"
      "#if LANES == 1\n"
      "  return {0}_distance(({1})(p.x, p.y, p.z), t);\n"
      "#else\n{2}"
      "#endif\n"
      "}}\n\n",
      name, vector3,
      packets ? fmt::format("  return {}_distance_packet(p.x, p.y, p.z, t);\n", name)
              : fmt::format(fmt::runtime(distance_lanes), name, vector3));
  if (program.module.color_function >= 0) {
    const char* color_lanes =
        "  real x[LANES], y[LANES], z[LANES], r[LANES], g[LANES], b[LANES];\n"
        "  VSTORE_LANES(p.x, 0, x);\n"
        "  VSTORE_LANES(p.y, 0, y);\n"
        "  VSTORE_LANES(p.z, 0, z);\n"
        "  for (int lane = 0; lane < LANES; ++lane) {{\n"
        "    const {1} c = {0}_color(({1})(x[lane], y[lane], z[lane]), t);\n"
        "    r[lane] = c.x;\n"
        "    g[lane] = c.y;\n"
        "    b[lane] = c.z;\n"
        "  }}\n"
        "  return (vec3v){{VLOAD_LANES(0, r), VLOAD_LANES(0, g), VLOAD_LANES(0, b)}};\n";
    code += fmt::format(
        "/* The user's colour on each lane of a packet. */\n"
        "vec3v {0}_color_lanes(vec3v p, real t) {{\n"
        "#if LANES == 1\n"
        "  const {1} c = {0}_color(({1})(p.x, p.y, p.z), t);\n"
        "  return (vec3v){{c.x, c.y, c.z}};\n"
        "#else\n{2}"
        "#endif\n"
        "}}\n\n",
        name, vector3,
        packets ? fmt::format("  return {}_color_packet(p.x, p.y, p.z, t);\n", name)
                : fmt::format(fmt::runtime(color_lanes), name, vector3));
  }
  return code;
}

// The user's code in one precision: the scalar translation, the packet one where it exists (a
// comment says why not where it does not), and the wrappers the distance function calls.
std::string translated(const GlslProgram& program, bool double_precision) {
  glsl::TranslationOptions options;
  options.prefix = program.name;
  options.uniforms = program.uniforms;
  options.double_precision = double_precision;
  const glsl::PacketTranslation packets = glsl::translate_to_packets(program.module, options);
  const std::string packet_part =
      packets.code.empty()
          ? fmt::format("/* {} runs one lane of a packet at a time: {}. */\n", program.name, packets.obstacle)
          : fmt::format("#if LANES > 1\n/* {} as packets: every float a vector of the packet's lanes. */\n{}#endif\n",
                        program.name, packets.code);
  return glsl::translate_to_opencl(program.module, options) + packet_part +
         lane_wrappers(program, double_precision ? "double3" : "float3", !packets.code.empty());
}

}  // namespace

std::string glsl_functions(const Node& root) {
  std::vector<const GlslProgram*> programs;
  std::set<std::string> names;
  collect_programs(root, programs, names);
  std::string code;
  for (const GlslProgram* program : programs) {
    const std::string in_double = translated(*program, true);
    const std::string in_float = translated(*program, false);
    // Its #line directives name the user's file; the generated code after it names itself again.
    code += fmt::format(
        "/* User GLSL ({}), translated (glsl/opencl_translation). */\n#ifdef DOUBLE_PRECISION\n{}#else\n{}"
        "#endif\n#line 1 \"generated scene\"\n",
        program->module.file_name, in_double, in_float);
  }
  return code;
}

}  // namespace clmarch

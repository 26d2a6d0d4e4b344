// Emitting glsl nodes' translated code.
#include "codegen/glsl_code.hpp"

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

// The user's code branches and loops per point, which a packet's vector types cannot: it runs one
// lane at a time through private arrays (OpenCL C has no run-time index of a vector's lanes).
std::string lane_wrappers(const GlslProgram& program, std::string_view vector3) {
  const std::string& name = program.name;
  std::string code = fmt::format(
      "/* The user's distance on each lane of a packet. */\n"
      "vfloat {0}_distance_lanes(vec3v p, real t) {{\n"
      "#if LANES == 1\n"
      "  return {0}_distance(({1})(p.x, p.y, p.z), t);\n"
      "#else\n"
      "  real x[LANES], y[LANES], z[LANES], d[LANES];\n"
      "  VSTORE_LANES(p.x, 0, x);\n"
      "  VSTORE_LANES(p.y, 0, y);\n"
      "  VSTORE_LANES(p.z, 0, z);\n"
      "  for (int lane = 0; lane < LANES; ++lane) d[lane] = {0}_distance(({1})(x[lane], y[lane], z[lane]), t);\n"
      "  return VLOAD_LANES(0, d);\n"
      "#endif\n"
      "}}\n\n",
      name, vector3);
  if (program.module.color_function >= 0) {
    code += fmt::format(
        "/* The user's colour on each lane of a packet. */\n"
        "vec3v {0}_color_lanes(vec3v p, real t) {{\n"
        "#if LANES == 1\n"
        "  const {1} c = {0}_color(({1})(p.x, p.y, p.z), t);\n"
        "  return (vec3v){{c.x, c.y, c.z}};\n"
        "#else\n"
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
        "  return (vec3v){{VLOAD_LANES(0, r), VLOAD_LANES(0, g), VLOAD_LANES(0, b)}};\n"
        "#endif\n"
        "}}\n\n",
        name, vector3);
  }
  return code;
}

}  // namespace

std::string glsl_functions(const Node& root) {
  std::vector<const GlslProgram*> programs;
  std::set<std::string> names;
  collect_programs(root, programs, names);
  std::string code;
  for (const GlslProgram* program : programs) {
    glsl::TranslationOptions options;
    options.prefix = program->name;
    options.uniforms = program->uniforms;
    options.double_precision = true;
    const std::string in_double =
        glsl::translate_to_opencl(program->module, options) + lane_wrappers(*program, "double3");
    options.double_precision = false;
    const std::string in_float =
        glsl::translate_to_opencl(program->module, options) + lane_wrappers(*program, "float3");
    // Its #line directives name the user's file; the generated code after it names itself again.
    code += fmt::format(
        "/* User GLSL ({}), translated (glsl/opencl_translation). */\n#ifdef DOUBLE_PRECISION\n{}#else\n{}"
        "#endif\n#line 1 \"generated scene\"\n",
        program->module.file_name, in_double, in_float);
  }
  return code;
}

}  // namespace clmarch

// The packet translation of a module (opencl_packets.hpp): the functions' names and return types,
// the globals each writes, the globals' struct, each function through packets::PacketEmitter, and
// the entry points.
#include "glsl/opencl_packets.hpp"

#include "glsl/packet_emitter.hpp"

#include <fmt/format.h>

namespace clmarch::glsl {
namespace {

using opencl::Scope;
using packets::is_real;
using packets::is_uniform_scalar;
using packets::ModuleInfo;
using packets::PacketEmitter;
using packets::Unsupported;

std::string packet_c_type(const Type& type) {
  return is_real(type) ? "vfloat" : type.scalar == Scalar::Uint ? "uint" : "int";
}

// Each function's C name and return type (a vector or matrix comes back as the components of a
// struct), and the globals it and its callees write, which callees before callers allow in order.
void describe_functions(const Module& module, Scope& scope, ModuleInfo& info) {
  for (size_t i = 0; i < module.functions.size(); ++i) {
    const Function& function = module.functions[i];
    info.names.push_back(scope.unique_name(fmt::format("{}{}", function.name, i)));
    const Type& result = function.return_type;
    if (result.is_void()) {
      info.return_types.emplace_back("void");
    } else if (is_real(result) && result.components() > 1) {
      info.return_types.push_back(
          scope.helper(fmt::format("components{}", result.components()), [&](const std::string& name) {
            return fmt::format("typedef struct {{ vfloat c[{}]; }} {};\n", result.components(), name);
          }));
    } else if (is_real(result) || is_uniform_scalar(result)) {
      info.return_types.push_back(packet_c_type(result));
    } else {
      packets::unsupported(function.location, fmt::format("function '{}' returns a struct or an array", function.name));
    }
    packets::Writes writes;
    packets::collect_writes(module, info.globals_written, function.body, writes);
    std::set<int> globals;
    for (int variable : writes.written) {
      if (module.variables[variable].storage == Storage::Global) globals.insert(variable);
    }
    info.globals_written.push_back(globals);
  }
}

// The globals, as the lane-at-a-time translation has them: a struct each call of an entry point
// initialises.
std::string packet_globals_struct(const Module& module, Scope& scope) {
  std::string members;
  for (const Stmt& global : module.globals) {
    const Variable& variable = module.variables[global.variable];
    if (!is_real(variable.type) && !is_uniform_scalar(variable.type)) {
      packets::unsupported(variable.location, fmt::format("global '{}' of a type other than float, vectors, "
                                                          "matrices, int, uint and bool",
                                                          variable.name));
    }
    for (int i = 0; i < variable.type.components(); ++i) {
      members += fmt::format("  {} {}_{};\n", packet_c_type(variable.type), variable.name,
                             variable.type.components() == 1 ? "" : fmt::format("c{}", i));
    }
  }
  if (members.empty()) return "";
  return scope.helper(
      "globals", [&](const std::string& name) { return fmt::format("typedef struct {{\n{}}} {};\n", members, name); });
}

std::string packet_code(const Module& module, const TranslationOptions& options) {
  const Function& distance = module.functions[module.distance_function];
  if (module.variables[distance.parameters.at(0)].qualifier != ParameterQualifier::In) {
    packets::unsupported(distance.location, "the distance function's point is an out or inout parameter");
  }
  TranslationOptions packet_options = options;
  packet_options.prefix = options.prefix + "_packet";
  Scope scope(module, packet_options);
  ModuleInfo info;
  describe_functions(module, scope, info);
  info.globals_type = packet_globals_struct(module, scope);

  opencl::Writer functions(module.file_name);
  for (size_t i = 0; i < module.functions.size(); ++i)
    PacketEmitter(scope, info).function(static_cast<int>(i), functions);
  opencl::Writer initialisers(module.file_name);
  if (!info.globals_type.empty()) {
    initialisers.indent();
    initialisers.line(fmt::format("{} globals_value;", info.globals_type));
    initialisers.line(fmt::format("{}* globals = &globals_value;", info.globals_type));
    PacketEmitter(scope, info).global_initialisers(initialisers);
  }

  const std::string& prefix = options.prefix;
  std::string code;
  for (const std::string& definition : scope.definitions()) code += definition;
  code += functions.text();
  const std::string arguments = info.globals_type.empty() ? "iTime, x, y, z" : "iTime, globals, x, y, z";
  const std::string generated = fmt::format("#line 1 \"{}_packet (translated)\"\n", prefix);
  code += fmt::format("vfloat {}_distance_packet(vfloat x, vfloat y, vfloat z, real iTime) {{\n", prefix);
  code += initialisers.text() + generated;
  code += fmt::format("  return {}({}){};\n}}\n", info.names[module.distance_function], arguments,
                      distance.return_type.components() > 1 ? ".c[0]" : "");
  if (module.color_function >= 0) {
    code += fmt::format("vec3v {}_color_packet(vfloat x, vfloat y, vfloat z, real iTime) {{\n", prefix);
    code += initialisers.text() + generated;
    code += fmt::format("  const {} c = {}({});\n  return (vec3v){{c.c[0], c.c[1], c.c[2]}};\n}}\n",
                        info.return_types[module.color_function], info.names[module.color_function], arguments);
  }
  return code;
}

}  // namespace

PacketTranslation translate_to_packets(const Module& module, const TranslationOptions& options) {
  try {
    return {packet_code(module, options), ""};
  } catch (const Unsupported& reason) {
    return {"", reason.reason};
  }
}

}  // namespace clmarch::glsl

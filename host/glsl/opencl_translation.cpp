// The OpenCL translation of a module (opencl_translation.hpp): names, the globals' struct, the user
// functions in the module's order, and the entry points, assembled after the typedefs and helpers
// the functions asked for.
#include "glsl/opencl_translation.hpp"

#include "glsl/opencl_emitter.hpp"
#include "glsl/opencl_scope.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace clmarch::glsl {

namespace {

using opencl::FunctionEmitter;
using opencl::ProgramInfo;
using opencl::Scope;
using opencl::Writer;

bool reads_globals(const Module& module, const Expr& expr, const std::vector<bool>& needs) {
  if (expr.kind == ExprKind::Variable) {
    const Variable& variable = module.variables[expr.variable];
    if (variable.storage == Storage::Global || variable.storage == Storage::GlobalConst) return true;
    if (variable.uniform == UniformKind::Time || variable.uniform == UniformKind::Frame) return true;
  }
  if (expr.kind == ExprKind::Call && needs[expr.function]) return true;
  return std::any_of(expr.operands.begin(), expr.operands.end(),
                     [&](const Expr& operand) { return reads_globals(module, operand, needs); });
}

bool is_global(const Module& module, int variable) {
  return variable >= 0 && (module.variables[variable].storage == Storage::Global ||
                           module.variables[variable].storage == Storage::GlobalConst);
}

bool writes_globals(const Module& module, const Expr& expr, const std::vector<bool>& writes) {
  const bool increments =
      expr.kind == ExprKind::Operation && (expr.op == Operator::PreIncrement || expr.op == Operator::PreDecrement ||
                                           expr.op == Operator::PostIncrement || expr.op == Operator::PostDecrement);
  if ((expr.kind == ExprKind::Assign || increments) && is_global(module, root_variable(expr.operands[0]))) return true;
  if (expr.kind == ExprKind::Call) {
    if (writes[expr.function]) return true;
    const Function& function = module.functions[expr.function];
    for (size_t i = 0; i < function.parameters.size(); ++i) {
      if (module.variables[function.parameters[i]].qualifier != ParameterQualifier::In &&
          is_global(module, root_variable(expr.operands[i]))) {
        return true;
      }
    }
  }
  if (expr.kind == ExprKind::BuiltinCall && expr.builtin == Builtin::Modf &&
      is_global(module, root_variable(expr.operands[1]))) {
    return true;
  }
  return std::any_of(expr.operands.begin(), expr.operands.end(),
                     [&](const Expr& operand) { return writes_globals(module, operand, writes); });
}

// Whether any expression of the statement (and those inside it) satisfies test.
template <typename Test>
bool any_expression(const Stmt& stmt, const Test& test) {
  if ((stmt.has_value || stmt.kind == StmtKind::Expression || stmt.kind == StmtKind::If ||
       stmt.kind == StmtKind::Switch || (stmt.kind == StmtKind::Loop && stmt.has_condition)) &&
      test(stmt.expression)) {
    return true;
  }
  if (stmt.has_step && test(stmt.step)) return true;
  return std::any_of(stmt.body.begin(), stmt.body.end(), [&](const Stmt& s) { return any_expression(s, test); });
}

// C names of the functions: the GLSL name, with the parameters' types where it is overloaded.
std::vector<std::string> function_names(const Module& module, Scope& scope) {
  std::map<std::string, int> uses;
  for (const Function& function : module.functions) ++uses[function.name];
  std::vector<std::string> names;
  for (const Function& function : module.functions) {
    std::string wanted = function.name;
    if (uses[function.name] > 1) {
      if (function.parameters.empty()) wanted += "_void";
      for (int parameter : function.parameters) {
        wanted += '_';
        wanted += scope.glsl_name(module.variables[parameter].type);
      }
    }
    names.push_back(scope.unique_name(wanted));
  }
  return names;
}

ProgramInfo program_info(const Module& module, Scope& scope) {
  ProgramInfo info;
  info.function_names = function_names(module, scope);
  const size_t count = module.functions.size();
  info.needs_globals.assign(count, false);
  info.writes_globals.assign(count, false);
  // Callees come before their callers.
  for (size_t i = 0; i < count; ++i) {
    const Stmt& body = module.functions[i].body;
    info.needs_globals[i] =
        any_expression(body, [&](const Expr& e) { return reads_globals(module, e, info.needs_globals); });
    info.writes_globals[i] =
        any_expression(body, [&](const Expr& e) { return writes_globals(module, e, info.writes_globals); });
  }
  return info;
}

bool reads_uniform(const Module& module, const Expr& expr, UniformKind kind) {
  if (expr.kind == ExprKind::Variable && module.variables[expr.variable].storage == Storage::Uniform &&
      module.variables[expr.variable].uniform == kind) {
    return true;
  }
  return std::any_of(expr.operands.begin(), expr.operands.end(),
                     [&](const Expr& operand) { return reads_uniform(module, operand, kind); });
}

bool uses_uniform(const Module& module, UniformKind kind) {
  auto reads = [&](const Expr& e) { return reads_uniform(module, e, kind); };
  return std::any_of(module.functions.begin(), module.functions.end(),
                     [&](const Function& f) { return any_expression(f.body, reads); }) ||
         std::any_of(module.globals.begin(), module.globals.end(),
                     [&](const Stmt& s) { return any_expression(s, reads); });
}

// The struct of the globals and of iTime and iFrame, which a call of an entry point initialises:
// OpenCL C 1.2 has no mutable program-scope variables.
std::string globals_struct(const Module& module, Scope& scope) {
  const bool time = uses_uniform(module, UniformKind::Time);
  const bool frame = uses_uniform(module, UniformKind::Frame);
  if (module.globals.empty() && !time && !frame) return "";
  return scope.helper("globals", [&](const std::string& name) {
    std::string body;
    if (time) body += fmt::format("  {} iTime;\n", scope.real());
    if (frame) body += "  int iFrame;\n";
    for (const Stmt& stmt : module.globals) {
      const Variable& variable = module.variables[stmt.variable];
      body += fmt::format("  {} {}_;\n", scope.type(variable.type), variable.name);
    }
    return fmt::format("typedef struct {{\n{}}} {};\n", body, name);
  });
}

// The number of lines of text.
int line_count(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

std::string translate_to_opencl(const Module& module, const TranslationOptions& options) {
  Scope scope(module, options);
  ProgramInfo info = program_info(module, scope);
  for (size_t i = 0; i < module.structs.size(); ++i) {
    Type type;
    type.struct_index = static_cast<int>(i);
    scope.type(type);
  }
  info.globals_type = globals_struct(module, scope);

  Writer functions(module.file_name);
  for (size_t i = 0; i < module.functions.size(); ++i) {
    FunctionEmitter emitter(scope, info, "globals");
    emitter.function(static_cast<int>(i), functions);
  }

  const std::string real = scope.real();
  const std::string prefix = options.prefix;
  Writer tail(module.file_name);
  std::string initialise;
  if (!info.globals_type.empty()) {
    initialise = scope.unique_name("initialise_globals");
    tail.line(fmt::format("void {}({}* globals, {} t) {{", initialise, info.globals_type, real));
    tail.indent();
    if (uses_uniform(module, UniformKind::Time)) tail.line("globals->iTime = t;");
    if (uses_uniform(module, UniformKind::Frame)) {
      tail.line(fmt::format("globals->iFrame = convert_int_sat_rtz(floor(t * {}));",
                            scope.scalar_literal(kFramesPerSecond, Scalar::Float)));
    }
    FunctionEmitter emitter(scope, info, "globals");
    emitter.global_initialisers(tail);
    tail.outdent();
    tail.line("}");
  }
  auto entry_point = [&](int function, const std::string& signature, const std::string& suffix) {
    tail.line(signature + " {");
    tail.indent();
    std::vector<std::string> arguments;
    if (info.needs_globals[function]) {
      tail.line(fmt::format("{} globals;", info.globals_type));
      tail.line(fmt::format("{}(&globals, t);", initialise));
      arguments.push_back("&globals");
    }
    const Variable& parameter = module.variables[module.functions[function].parameters.at(0)];
    arguments.push_back(parameter.qualifier == ParameterQualifier::In ? "p" : "&p");
    tail.line(fmt::format("return {}({}){};", info.function_names[function], fmt::join(arguments, ", "), suffix));
    tail.outdent();
    tail.line("}");
  };
  const Type& distance_type = module.functions[module.distance_function].return_type;
  entry_point(module.distance_function, fmt::format("{0} {1}_distance({0}3 p, {0} t)", real, prefix),
              distance_type.rows > 1 ? ".x" : "");
  if (module.color_function >= 0) {
    entry_point(module.color_function, fmt::format("{0}3 {1}_color({0}3 p, {0} t)", real, prefix), "");
  }

  // Generated parts name the translation in #line, user functions the user's file.
  std::string out = fmt::format("/* {}: the OpenCL C translation of {}. */\n", prefix, module.file_name);
  const std::string generated = fmt::format("\"{} (translated)\"", prefix);
  out += fmt::format("#line {} {}\n", line_count(out) + 2, generated);
  for (const std::string& definition : scope.definitions()) out += definition;
  out += functions.text();
  out += fmt::format("#line {} {}\n", line_count(out) + 2, generated);
  out += tail.text();
  return out;
}

}  // namespace clmarch::glsl

// GLSL's scalar functions on top of muparser's.
#include "scene/expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

double glsl_fract(double x) { return x - std::floor(x); }
double glsl_mod(double x, double y) { return x - y * std::floor(x / y); }
double glsl_clamp(double x, double low, double high) { return std::min(std::max(x, low), high); }
double glsl_mix(double a, double b, double t) { return a * (1.0 - t) + b * t; }
double glsl_step(double edge, double x) { return x < edge ? 0.0 : 1.0; }
double glsl_smoothstep(double edge0, double edge1, double x) {
  const double s = glsl_clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}
double glsl_pow(double x, double y) { return std::pow(x, y); }
double glsl_floor(double x) { return std::floor(x); }
double glsl_ceil(double x) { return std::ceil(x); }

/// GLSL's atan(y) and atan(y, x); muparser names one callback a name, so both arities share it.
double glsl_atan(const double* args, int count) {
  if (count == 1) return std::atan(args[0]);
  if (count == 2) return std::atan2(args[0], args[1]);
  throw mu::ParserError(fmt::format("atan takes one argument (y) or two (y, x), not {}", count));
}

/// GLSL's length of a float, vec2 or vec3 given as its components.
double glsl_length(const double* args, int count) {
  if (count == 1) return std::abs(args[0]);
  if (count == 2) return std::hypot(args[0], args[1]);
  if (count == 3) return std::hypot(args[0], args[1], args[2]);
  throw mu::ParserError(fmt::format("length takes one to three values, not {}", count));
}

/// A parser with GLSL's functions besides muparser's own (which already has abs, sign, min, max,
/// sqrt, exp, log, the trigonometric functions and pi as _pi).
void add_glsl_functions(mu::Parser& parser) {
  parser.DefineFun("floor", glsl_floor);
  parser.DefineFun("ceil", glsl_ceil);
  parser.DefineFun("fract", glsl_fract);
  parser.DefineFun("mod", glsl_mod);
  parser.DefineFun("clamp", glsl_clamp);
  parser.DefineFun("mix", glsl_mix);
  parser.DefineFun("step", glsl_step);
  parser.DefineFun("smoothstep", glsl_smoothstep);
  parser.DefineFun("pow", glsl_pow);
  parser.DefineFun("atan", glsl_atan);
  parser.DefineFun("length", glsl_length);
  parser.DefineConst("pi", M_PI);
}

std::vector<std::string> function_names() {
  mu::Parser parser;
  add_glsl_functions(parser);
  std::vector<std::string> names;
  for (const auto& [name, callback] : parser.GetFunDef()) names.push_back(name);
  return names;
}

}  // namespace

double evaluate_expression(const std::string& text, const std::vector<ExpressionVariable>& variables) {
  try {
    mu::Parser parser;
    add_glsl_functions(parser);
    std::vector<double> values;
    values.reserve(variables.size());  // DefineVar keeps pointers into it
    for (const auto& [name, value] : variables) {
      values.push_back(value);
      parser.DefineVar(name, &values.back());
    }
    parser.SetExpr(text);
    return parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    // A name it does not know: say which exist.
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN) throw ExpressionError(fmt::format("{}; {}", e.GetMsg(), expression_vocabulary(variables)));
    throw ExpressionError(e.GetMsg());
  }
}

std::string expression_vocabulary(const std::vector<ExpressionVariable>& variables) {
  std::vector<std::string> names;
  for (const auto& [name, value] : variables) names.push_back(name);
  return fmt::format("an expression may use the variable{} {}, the constant pi and the functions {}",
                     names.size() == 1 ? "" : "s", fmt::join(names, ", "), fmt::join(function_names(), ", "));
}

}  // namespace clmarch

// Expressions in scene files: muparser's syntax with GLSL's scalar functions, so that a shader
// author's `fract(t)`, `mod(t, 2)` or `smoothstep(0, 1, t)` reads as it does in a shader.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {

/// An expression that does not parse or evaluate: muparser's message, and for a name it does not
/// know what an expression may name (expression_vocabulary).
class ExpressionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A variable an expression may name, and its value.
using ExpressionVariable = std::pair<std::string, double>;

/// The value of text with variables set. GLSL's abs, sign, floor, ceil, fract, mod (x - y floor(x / y)),
/// min, max, clamp, mix, step, smoothstep, pow, sqrt, exp, log (natural), sin, cos, tan, asin,
/// acos, atan (of y, or of y and x), length (of one to three values), muparser's other functions
/// and the constant pi. Throws ExpressionError.
double evaluate_expression(const std::string& text, const std::vector<ExpressionVariable>& variables);

/// An expression parsed once and evaluated at many values of its variables: the reference's color
/// expressions, at every hit. Not thread-safe: one a thread.
class CompiledExpression {
 public:
  /// Throws ExpressionError as evaluate_expression does.
  CompiledExpression(const std::string& text, const std::vector<std::string>& variable_names);
  ~CompiledExpression();
  CompiledExpression(const CompiledExpression&) = delete;
  CompiledExpression& operator=(const CompiledExpression&) = delete;
  /// The value with the variables at values, in the order of variable_names.
  double operator()(const std::vector<double>& values);

 private:
  struct Parser;
  std::unique_ptr<Parser> parser_;
};

/// " (did you mean t? ...)" when name is what shaders call the time (iTime, time, u_time) and t is
/// among variables; else empty.
std::string variable_suggestion(const std::string& name, const std::vector<std::string>& variables);

/// "variables t; constants pi; functions abs, acos, ...": what an expression with these variables
/// may name, for error messages.
std::string expression_vocabulary(const std::vector<ExpressionVariable>& variables);

/// An expression as a tree, for the code generator (a color expression becomes OpenCL C): numbers,
/// variables, + - * / ^, unary minus and calls of GLSL's functions. muparser's other syntax
/// (comparisons, ?:, its own functions) has no tree.
struct ExpressionTree {
  enum class Kind { Number, Variable, Negate, Add, Subtract, Multiply, Divide, Power, Call };
  Kind kind = Kind::Number;
  double number = 0.0;
  /// Variable: its name (pi is the number); Call: the function's.
  std::string name;
  std::vector<ExpressionTree> operands;
};

/// The tree of text, whose variables are among variable_names; throws ExpressionError naming
/// what it cannot take and where (the 1-based character).
ExpressionTree parse_expression_tree(const std::string& text, const std::vector<std::string>& variable_names);

}  // namespace clmarch

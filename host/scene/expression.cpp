// GLSL's scalar functions on top of muparser's.
#include "scene/expression.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iterator>

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

/// Names shaders and other tools give the time, which expressions call t.
constexpr const char* kTimeNames[] = {"iTime", "time", "u_time", "iGlobalTime", "Time", "T"};

}  // namespace

std::string variable_suggestion(const std::string& name, const std::vector<std::string>& variables) {
  if (std::find(variables.begin(), variables.end(), "t") == variables.end()) return {};
  for (const char* time : kTimeNames) {
    if (name == time) return fmt::format(" (did you mean t? expressions call the time in seconds t, not {})", name);
  }
  return {};
}

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
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN) {
      std::vector<std::string> names;
      for (const auto& [name, value] : variables) names.push_back(name);
      throw ExpressionError(fmt::format("{}{}; {}", e.GetMsg(), variable_suggestion(e.GetToken(), names),
                                        expression_vocabulary(variables)));
    }
    throw ExpressionError(e.GetMsg());
  }
}

struct CompiledExpression::Parser {
  mu::Parser parser;
  std::vector<double> values;
};

CompiledExpression::CompiledExpression(const std::string& text, const std::vector<std::string>& variable_names)
    : parser_(std::make_unique<Parser>()) {
  parser_->values.resize(variable_names.size());
  try {
    add_glsl_functions(parser_->parser);
    for (std::size_t i = 0; i < variable_names.size(); ++i)
      parser_->parser.DefineVar(variable_names[i], &parser_->values[i]);
    parser_->parser.SetExpr(text);
  } catch (const mu::Parser::exception_type& e) {
    throw ExpressionError(e.GetMsg());
  }
}

CompiledExpression::~CompiledExpression() = default;

double CompiledExpression::operator()(const std::vector<double>& values) {
  std::copy(values.begin(), values.end(), parser_->values.begin());
  try {
    return parser_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw ExpressionError(e.GetMsg());
  }
}

std::string expression_vocabulary(const std::vector<ExpressionVariable>& variables) {
  std::vector<std::string> names;
  names.reserve(variables.size());
  for (const auto& [name, value] : variables) names.push_back(name);
  return fmt::format("an expression may use the variable{} {}, the constant pi and the functions {}",
                     names.size() == 1 ? "" : "s", fmt::join(names, ", "), fmt::join(function_names(), ", "));
}

namespace {

/// The functions a tree may call, and how many arguments each takes (at least, at most).
struct TreeFunction {
  const char* name;
  int least;
  int most;
};
constexpr TreeFunction kTreeFunctions[] = {
    {"abs", 1, 1}, {"sign", 1, 1}, {"floor", 1, 1}, {"ceil", 1, 1}, {"fract", 1, 1},  {"mod", 2, 2},
    {"min", 2, 2}, {"max", 2, 2},  {"clamp", 3, 3}, {"mix", 3, 3},  {"step", 2, 2},   {"smoothstep", 3, 3},
    {"pow", 2, 2}, {"sqrt", 1, 1}, {"exp", 1, 1},   {"log", 1, 1},  {"sin", 1, 1},    {"cos", 1, 1},
    {"tan", 1, 1}, {"asin", 1, 1}, {"acos", 1, 1},  {"atan", 1, 2}, {"length", 1, 3},
};

/// Recursive descent with muparser's precedence: unary minus binds looser than ^ (-2^2 = -4), ^ is
/// right-associative and takes a unary operand (2^-1).
class TreeParser {
 public:
  TreeParser(const std::string& text, const std::vector<std::string>& variables) : text_(text), variables_(variables) {}

  ExpressionTree parse() {
    ExpressionTree tree = sum();
    skip_space();
    if (at_ < text_.size()) fail(fmt::format("'{}' is not taken here", text_[at_]));
    return tree;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    // Only the functions a tree takes: muparser's others (sinh, rint, avg, ...) would be refused.
    std::vector<const char*> functions;
    for (const TreeFunction& f : kTreeFunctions) functions.push_back(f.name);
    throw ExpressionError(
        fmt::format("{} at character {} (a color expression takes numbers, the variables {}, pi, + - * / ^, "
                    "parentheses and the functions {})",
                    what, at_ + 1, fmt::join(variables_, ", "), fmt::join(functions, ", ")));
  }

  void skip_space() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }

  bool take(char c) {
    skip_space();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }

  static ExpressionTree node(ExpressionTree::Kind kind, std::vector<ExpressionTree> operands) {
    ExpressionTree tree;
    tree.kind = kind;
    tree.operands = std::move(operands);
    return tree;
  }

  ExpressionTree sum() {
    ExpressionTree tree = product();
    for (;;) {
      if (take('+')) {
        tree = node(ExpressionTree::Kind::Add, {std::move(tree), product()});
      } else if (take('-')) {
        tree = node(ExpressionTree::Kind::Subtract, {std::move(tree), product()});
      } else {
        return tree;
      }
    }
  }

  ExpressionTree product() {
    ExpressionTree tree = unary();
    for (;;) {
      if (take('*')) {
        tree = node(ExpressionTree::Kind::Multiply, {std::move(tree), unary()});
      } else if (take('/')) {
        tree = node(ExpressionTree::Kind::Divide, {std::move(tree), unary()});
      } else {
        return tree;
      }
    }
  }

  ExpressionTree unary() {
    if (take('-')) return node(ExpressionTree::Kind::Negate, {unary()});
    if (take('+')) return unary();
    return power();
  }

  ExpressionTree power() {
    ExpressionTree base = primary();
    if (take('^')) return node(ExpressionTree::Kind::Power, {std::move(base), unary()});
    return base;
  }

  ExpressionTree primary() {
    skip_space();
    if (take('(')) {
      ExpressionTree inner = sum();
      if (!take(')')) fail("a ')' is missing");
      return inner;
    }
    if (at_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[at_])) || text_[at_] == '.')) {
      const char* start = text_.c_str() + at_;
      char* end = nullptr;
      ExpressionTree number;
      number.number = std::strtod(start, &end);
      at_ += static_cast<std::size_t>(end - start);
      return number;
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) ++at_;
    if (start == at_)
      fail(at_ < text_.size() ? fmt::format("'{}' is not taken here", text_[at_])
                              : std::string("the expression ends early"));
    const std::string name = text_.substr(start, at_ - start);
    if (take('(')) return call(name, start);
    if (name == "pi") {
      ExpressionTree number;
      number.number = M_PI;
      return number;
    }
    if (std::find(variables_.begin(), variables_.end(), name) == variables_.end()) {
      at_ = start;
      fail(fmt::format("'{}' is no variable{}", name, variable_suggestion(name, variables_)));
    }
    ExpressionTree variable;
    variable.kind = ExpressionTree::Kind::Variable;
    variable.name = name;
    return variable;
  }

  ExpressionTree call(const std::string& name, std::size_t start) {
    const auto function = std::find_if(std::begin(kTreeFunctions), std::end(kTreeFunctions),
                                       [&](const TreeFunction& f) { return name == f.name; });
    ExpressionTree tree;
    tree.kind = ExpressionTree::Kind::Call;
    tree.name = name;
    if (!take(')')) {
      do {
        tree.operands.push_back(sum());
      } while (take(','));
      if (!take(')')) fail("a ')' is missing");
    }
    const int count = static_cast<int>(tree.operands.size());
    if (function == std::end(kTreeFunctions) || count < function->least || count > function->most) {
      at_ = start;
      fail(function == std::end(kTreeFunctions) ? fmt::format("'{}' is not a function a color expression takes", name)
                                                : fmt::format("{} does not take {} arguments", name, count));
    }
    return tree;
  }

  const std::string& text_;
  const std::vector<std::string>& variables_;
  std::size_t at_ = 0;
};

}  // namespace

ExpressionTree parse_expression_tree(const std::string& text, const std::vector<std::string>& variable_names) {
  return TreeParser(text, variable_names).parse();
}

}  // namespace clmarch

// Color patterns as OpenCL C.
#include "codegen/color_pattern_code.hpp"

#include "scene/expression.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>
#include <vector>

namespace clmarch {
namespace {

/// A color expression's tree as a vfloat expression of q and the time's literal.
class ExpressionCode {
 public:
  ExpressionCode(const std::string& q, double time, Literals& lit) : q_(q), time_(time), lit_(lit) {}

  std::string operator()(const ExpressionTree& tree) {
    using Kind = ExpressionTree::Kind;
    switch (tree.kind) {
      case Kind::Number:
        return fmt::format("(vfloat)({})", lit_.f(tree.number));
      case Kind::Variable:
        return tree.name == "t" ? fmt::format("(vfloat)({})", lit_.f(time_)) : fmt::format("{}.{}", q_, tree.name);
      case Kind::Negate:
        return fmt::format("(-{})", (*this)(tree.operands[0]));
      case Kind::Add:
        return binary(tree, "+");
      case Kind::Subtract:
        return binary(tree, "-");
      case Kind::Multiply:
        return binary(tree, "*");
      case Kind::Divide:
        return binary(tree, "/");
      case Kind::Power:
        return fmt::format("pow({}, {})", (*this)(tree.operands[0]), (*this)(tree.operands[1]));
      case Kind::Call:
        return call(tree);
    }
    throw std::logic_error("an expression tree of no kind");
  }

 private:
  std::string binary(const ExpressionTree& tree, const char* op) {
    return fmt::format("({} {} {})", (*this)(tree.operands[0]), op, (*this)(tree.operands[1]));
  }

  /// GLSL's functions in OpenCL C: most by the same name; fract, mod and smoothstep by GLSL's
  /// formulas (OpenCL's fract takes a pointer, fmod truncates, smoothstep is open where edge0 >=
  /// edge1), atan of two as atan2, length by its components.
  std::string call(const ExpressionTree& tree) {
    std::vector<std::string> a;
    for (const ExpressionTree& operand : tree.operands) a.push_back((*this)(operand));
    const std::string& f = tree.name;
    if (f == "abs") return fmt::format("fabs({})", a[0]);
    if (f == "fract") return fmt::format("({0} - floor({0}))", a[0]);
    if (f == "mod") return fmt::format("({0} - {1} * floor({0} / {1}))", a[0], a[1]);
    if (f == "min") return fmt::format("fmin({}, {})", a[0], a[1]);
    if (f == "max") return fmt::format("fmax({}, {})", a[0], a[1]);
    if (f == "smoothstep") return fmt::format("glsl_smoothstep({}, {}, {})", a[0], a[1], a[2]);
    if (f == "atan" && a.size() == 2) return fmt::format("atan2({}, {})", a[0], a[1]);
    if (f == "length") {
      if (a.size() == 1) return fmt::format("fabs({})", a[0]);
      std::vector<std::string> squares;
      squares.reserve(a.size());
      for (const std::string& x : a) squares.push_back(fmt::format("{0} * {0}", x));
      return fmt::format("sqrt({})", fmt::join(squares, " + "));
    }
    return fmt::format("{}({})", f, fmt::join(a, ", "));
  }

  const std::string& q_;
  double time_;
  Literals& lit_;
};

std::string color_literal(const glm::dvec3& color, Literals& lit) { return fmt::format("v3_from({})", lit.f4(color)); }

}  // namespace

std::string pattern_color_code(const ColorPattern& pattern, const std::string& q, Literals& lit) {
  const char* axes[] = {"x", "y", "z"};
  switch (pattern.kind) {
    case ColorPattern::Kind::Checker:
      return fmt::format("pattern_checker({}, {}, {}, {})", q, lit.f(pattern.size),
                         color_literal(pattern.colors[0], lit), color_literal(pattern.colors[1], lit));
    case ColorPattern::Kind::Stripes:
      return fmt::format("pattern_stripes({}.{}, {}, {}, {})", q, axes[pattern.axis], lit.f(pattern.size),
                         color_literal(pattern.colors[0], lit), color_literal(pattern.colors[1], lit));
    case ColorPattern::Kind::Grid: {
      const std::string size = lit.f(pattern.size), half_width = lit.f(0.5 * pattern.line_width);
      std::vector<std::string> near;
      for (int axis = 0; axis < 3; ++axis) {
        if (pattern.grid_axes[axis])
          near.push_back(fmt::format("near_grid_line({}.{}, {}, {})", q, axes[axis], size, half_width));
      }
      return fmt::format("v3_select({}, {}, {})", color_literal(pattern.colors[0], lit),
                         color_literal(pattern.colors[1], lit), fmt::join(near, " | "));
    }
    case ColorPattern::Kind::Expression: {
      ExpressionCode code(q, pattern.time, lit);
      std::vector<std::string> channels;
      for (const std::string& text : pattern.expressions)
        channels.push_back(code(parse_expression_tree(text, {"x", "y", "z", "t"})));
      return fmt::format("v3({}, {}, {})", channels[0], channels[1], channels[2]);
    }
  }
  throw std::logic_error("a color pattern of no kind");
}

}  // namespace clmarch

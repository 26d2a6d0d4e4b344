// Checker, stripes, grid and color expressions at a point, in double; the expressions through
// muparser (scene/expression), independently of the kernels' translation of them.
#include "reference/reference_patterns.hpp"

#include "scene/expression.hpp"

#include <cmath>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace clmarch {
namespace {

bool is_odd(double whole) { return whole - 2.0 * std::floor(0.5 * whole) != 0.0; }

double cell_of(double v, double size) { return std::floor(v / size); }

/// A color expression's value at q, from this thread's parser of it (parsing costs more than
/// marching a ray).
double expression_at(const std::string& text, const glm::dvec3& q, double time) {
  thread_local std::unordered_map<std::string, std::unique_ptr<CompiledExpression>> compiled;
  std::unique_ptr<CompiledExpression>& expression = compiled[text];
  if (!expression)
    expression = std::make_unique<CompiledExpression>(text, std::vector<std::string>{"x", "y", "z", "t"});
  return (*expression)({q.x, q.y, q.z, time});
}

}  // namespace

glm::dvec3 reference_pattern_color(const ColorPattern& pattern, const glm::dvec3& q) {
  const double s = pattern.size;
  switch (pattern.kind) {
    case ColorPattern::Kind::Checker:
      return pattern.colors[is_odd(cell_of(q.x, s) + cell_of(q.y, s) + cell_of(q.z, s)) ? 1 : 0];
    case ColorPattern::Kind::Stripes:
      return pattern.colors[is_odd(cell_of(q[pattern.axis], s)) ? 1 : 0];
    case ColorPattern::Kind::Grid: {
      bool line = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double c = q[axis];
        line =
            line || (pattern.grid_axes[axis] && std::abs(c - s * std::floor(c / s + 0.5)) < 0.5 * pattern.line_width);
      }
      return pattern.colors[line ? 1 : 0];
    }
    case ColorPattern::Kind::Expression: {
      glm::dvec3 color;
      for (int c = 0; c < 3; ++c) color[c] = expression_at(pattern.expressions[c], q, pattern.time);
      return color;
    }
  }
  return glm::dvec3(0.0);
}

}  // namespace clmarch

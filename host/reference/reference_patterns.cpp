// Checker, stripes, grid and color expressions at a point, in double; the expressions through
// muparser (scene/expression), independently of the kernels' translation of them.
#include "reference/reference_patterns.hpp"

#include "scene/expression.hpp"

#include <cmath>

namespace clmarch {
namespace {

bool is_odd(double whole) { return whole - 2.0 * std::floor(0.5 * whole) != 0.0; }

}  // namespace

glm::dvec3 reference_pattern_color(const ColorPattern& pattern, const glm::dvec3& q) {
  const double s = pattern.size;
  switch (pattern.kind) {
    case ColorPattern::Kind::Checker:
      return pattern.colors[is_odd(std::floor(q.x / s) + std::floor(q.y / s) + std::floor(q.z / s)) ? 1 : 0];
    case ColorPattern::Kind::Stripes: return pattern.colors[is_odd(std::floor(q[pattern.axis] / s)) ? 1 : 0];
    case ColorPattern::Kind::Grid: {
      bool line = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double c = q[axis];
        line = line || (pattern.grid_axes[axis] && std::abs(c - s * std::floor(c / s + 0.5)) < 0.5 * pattern.line_width);
      }
      return pattern.colors[line ? 1 : 0];
    }
    case ColorPattern::Kind::Expression: {
      glm::dvec3 color;
      for (int c = 0; c < 3; ++c) color[c] = evaluate_expression(pattern.expressions[c], {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"t", pattern.time}});
      return color;
    }
  }
  return glm::dvec3(0.0);
}

}  // namespace clmarch

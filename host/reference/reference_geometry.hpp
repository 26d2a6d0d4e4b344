// Plane and space geometry of the reference's distance functions, in double: distances to
// segments, arcs, triangles and convex polygons, from which the shapes are built as constructions.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace clmarch::geometry {

/// The distance from p to the segment a-b (in the plane or in space); a point where a = b.
template <class Vec>
double distance_to_segment(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double length2 = glm::dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

/// The distance from p to the arc of the circle (center, radius) between the polar angles from
/// and to (radians, -pi <= from <= to <= pi, measured as atan2(y, x) about center).
inline double distance_to_arc(const glm::dvec2& p, const glm::dvec2& center, double radius, double from, double to) {
  const glm::dvec2 l = p - center;
  const double angle = std::atan2(l.y, l.x);
  if (angle >= from && angle <= to) return std::abs(glm::length(l) - radius);
  const glm::dvec2 first = center + radius * glm::dvec2(std::cos(from), std::sin(from));
  const glm::dvec2 last = center + radius * glm::dvec2(std::cos(to), std::sin(to));
  return std::min(glm::length(p - first), glm::length(p - last));
}

/// The distance from p to the triangle abc: to its plane where p projects inside it, else to the
/// nearest edge.
inline double distance_to_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const bool inside = glm::dot(glm::cross(b - a, p - a), n) >= 0.0 && glm::dot(glm::cross(c - b, p - b), n) >= 0.0 &&
                      glm::dot(glm::cross(a - c, p - c), n) >= 0.0;
  if (inside) return std::abs(glm::dot(p - a, n)) / glm::length(n);
  return std::min({distance_to_segment(p, a, b), distance_to_segment(p, b, c), distance_to_segment(p, c, a)});
}

/// The signed distance to a convex polygon given by its vertices in order, in the plane: the
/// nearest edge's distance, negative inside.
inline double convex_polygon_distance(const glm::dvec2& p, const std::vector<glm::dvec2>& corners) {
  double nearest = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const glm::dvec2& a = corners[i];
    const glm::dvec2& b = corners[(i + 1) % corners.size()];
    nearest = std::min(nearest, distance_to_segment(p, a, b));
    const glm::dvec2 edge = b - a;
    // Counter-clockwise corners: inside is left of every edge.
    if (edge.x * (p.y - a.y) - edge.y * (p.x - a.x) < 0.0) inside = false;
  }
  return inside ? -nearest : nearest;
}

/// A 2D signed distance d turned into a prism of half height h along the third axis y.
inline double extrude(double d, double y, double h) {
  const glm::dvec2 w(d, std::abs(y) - h);
  return std::min(std::max(w.x, w.y), 0.0) + glm::length(glm::max(w, 0.0));
}

}  // namespace clmarch::geometry

// Closed-form ray hits: quadratic for the sphere, slabs for the box, a linear equation for the plane
// and a robustly isolated quartic for the torus.
#include "analytic_intersections.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace clmarch {
namespace {

// Both roots of a t^2 + 2 b t + c = 0 (a > 0) in ascending order, without cancellation.
std::optional<std::pair<double, double>> solve_quadratic(double a, double b, double c) {
  const double disc = b * b - a * c;
  if (disc < 0.0) return std::nullopt;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  if (q == 0.0) return std::pair{0.0, 0.0};
  const double t0 = q / a;
  const double t1 = c / q;
  return std::pair{std::min(t0, t1), std::max(t0, t1)};
}

// Polynomials as coefficients, c[i] multiplying s^i.
using Poly = std::vector<double>;

double evaluate(const Poly& c, double s) {
  double v = 0.0;
  for (auto it = c.rbegin(); it != c.rend(); ++it) v = v * s + *it;
  return v;
}

// Halves [a, b] around the sign change until no double lies between the ends.
double bisect(const Poly& c, double a, double b, double fa) {
  for (;;) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) return std::abs(fa) <= std::abs(evaluate(c, b)) ? a : b;
    const double fm = evaluate(c, m);
    if (fm == 0.0) return m;
    if ((fm < 0.0) == (fa < 0.0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
}

// Real roots in [lo, hi], ascending. Between consecutive roots of the derivative the polynomial is
// monotonic, so each sign change there brackets exactly one root: no root can be skipped.
std::vector<double> roots_in(const Poly& c, double lo, double hi) {
  std::vector<double> roots;
  if (c.size() == 2) {
    if (c[1] != 0.0) {
      const double s = -c[0] / c[1];
      if (s >= lo && s <= hi) roots.push_back(s);
    }
    return roots;
  }
  Poly derivative(c.size() - 1);
  for (std::size_t i = 1; i < c.size(); ++i) derivative[i - 1] = c[i] * static_cast<double>(i);
  std::vector<double> knots{lo};
  for (double s : roots_in(derivative, lo, hi)) knots.push_back(s);
  knots.push_back(hi);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const double a = knots[i], b = knots[i + 1];
    const double fa = evaluate(c, a), fb = evaluate(c, b);
    if (fa == 0.0)
      roots.push_back(a);
    else if (fb != 0.0 && (fa < 0.0) != (fb < 0.0))
      roots.push_back(bisect(c, a, b, fa));
  }
  if (evaluate(c, hi) == 0.0) roots.push_back(hi);
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  return roots;
}

}  // namespace

std::optional<double> intersect_sphere(const glm::dvec3& o, const glm::dvec3& d, const Sphere& sphere) {
  const glm::dvec3 oc = o - sphere.center;
  const auto roots = solve_quadratic(glm::dot(d, d), glm::dot(oc, d), glm::dot(oc, oc) - sphere.radius * sphere.radius);
  if (!roots) return std::nullopt;
  if (roots->first > 0.0) return roots->first;
  if (roots->second > 0.0) return roots->second;
  return std::nullopt;
}

std::optional<double> intersect_box(const glm::dvec3& o, const glm::dvec3& d, const Box& box) {
  double t_enter = -std::numeric_limits<double>::infinity();
  double t_exit = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double lo = box.center[i] - box.half_size[i] - o[i];
    const double hi = box.center[i] + box.half_size[i] - o[i];
    // A ray parallel to the slab would divide 0 by 0 when it runs along a face.
    if (d[i] == 0.0) {
      if (lo > 0.0 || hi < 0.0) return std::nullopt;
      continue;
    }
    const double t0 = lo / d[i], t1 = hi / d[i];
    t_enter = std::max(t_enter, std::min(t0, t1));
    t_exit = std::min(t_exit, std::max(t0, t1));
  }
  if (t_enter > t_exit || t_exit <= 0.0) return std::nullopt;
  return t_enter > 0.0 ? t_enter : t_exit;
}

std::optional<double> intersect_plane(const glm::dvec3& o, const glm::dvec3& d, const Plane& plane) {
  const double denom = glm::dot(plane.normal, d);
  if (denom == 0.0) return std::nullopt;
  const double t = -(glm::dot(plane.normal, o) + plane.offset) / denom;
  if (t > 0.0) return t;
  return std::nullopt;
}

std::optional<double> intersect_torus(const glm::dvec3& o, const glm::dvec3& d, const Torus& torus) {
  const double R = torus.major_radius, r = torus.minor_radius;
  // Restart the ray where it enters the bounding sphere: near the torus the quartic's coefficients
  // stay O(R^4), so its roots keep full precision whatever the camera distance.
  const glm::dvec3 oc = o - torus.center;
  const double dd = glm::dot(d, d);
  const auto bound = solve_quadratic(dd, glm::dot(oc, d), glm::dot(oc, oc) - (R + r) * (R + r));
  if (!bound || bound->second <= 0.0) return std::nullopt;
  const double t0 = std::max(bound->first, 0.0);
  const glm::dvec3 p = oc + t0 * d;

  // |x|^2 + R^2 - r^2 = 2 R |x.xz| squared, with x = p + s d.
  const double B = 2.0 * glm::dot(p, d);
  const double C = glm::dot(p, p) + R * R - r * r;
  const double R4 = 4.0 * R * R;
  const Poly quartic{
      C * C - R4 * (p.x * p.x + p.z * p.z),
      2.0 * B * C - 2.0 * R4 * (p.x * d.x + p.z * d.z),
      B * B + 2.0 * dd * C - R4 * (d.x * d.x + d.z * d.z),
      2.0 * dd * B,
      dd * dd,
  };
  // The chord of the bounding sphere bounds s; the slack keeps a root at its far end inside.
  const double s_max = 2.0 * (R + r) / std::sqrt(dd) * (1.0 + 1e-9) + 1e-12;
  for (double s : roots_in(quartic, 0.0, s_max)) {
    const double t = t0 + s;
    if (t > 0.0) return t;
  }
  return std::nullopt;
}

}  // namespace clmarch

// Reference fractal primitives in double (formulas: docs/scene-format.md, "Fractals and terrain").
#include "reference/reference_fractals.hpp"

#include "scene/tiling_model.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

// Keeps acos and log finite at the centre, where the orbit can sit at exactly 0.
constexpr double kTinyRadius = 1e-30;

// Distances above this are capped before they meet the enclosing ball: the escape-time estimate
// grows like r log r / 2 far from the set and would overshoot there.
constexpr double kEstimateCap = 1.0;

}  // namespace

double sd_mandelbulb(const glm::dvec3& p, const Mandelbulb& bulb) {
  const double n = bulb.power;
  const glm::dvec3 c = p - bulb.center;
  glm::dvec3 z = c;
  double dr = 1.0;
  double r = glm::length(z);
  // z -> z^n + c in spherical form (theta from the z axis, phi about it); dr = |dz/dc| grows as
  // n r^(n-1) dr + 1. The orbit stops at the first |z| > bailout.
  for (int i = 0; i < bulb.iterations && r <= bulb.bailout; ++i) {
    const double theta = std::acos(std::clamp(z.z / std::max(r, kTinyRadius), -1.0, 1.0)) * n;
    const double phi = std::atan2(z.y, z.x) * n;
    const double r_n1 = std::pow(r, n - 1.0);
    dr = r_n1 * n * dr + 1.0;
    const double zr = r_n1 * r;
    const double sin_theta = std::sin(theta);
    z = zr * glm::dvec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta)) + c;
    r = glm::length(z);
  }
  r = std::max(r, kTinyRadius);
  const double estimate = 0.5 * std::log(r) * r / dr;
  return std::max(glm::length(c) - mandelbulb_radius(n), std::min(estimate, kEstimateCap));
}

double sd_sierpinski(const glm::dvec3& p, const Sierpinski& tetrahedron) {
  const glm::dvec3 c = p - tetrahedron.center;
  glm::dvec3 z = c / tetrahedron.size;
  const double s = tetrahedron.scale;
  for (int i = 0; i < tetrahedron.iterations; ++i) {
    // Reflections across x + y = 0, x + z = 0, y + z = 0 where the point lies on their far side.
    if (z.x + z.y < 0.0) z = glm::dvec3(-z.y, -z.x, z.z);
    if (z.x + z.z < 0.0) z = glm::dvec3(-z.z, z.y, -z.x);
    if (z.y + z.z < 0.0) z = glm::dvec3(z.x, -z.z, -z.y);
    z = z * s - glm::dvec3(s - 1.0);
  }
  const double planes = std::max({-z.x - z.y - z.z, z.x + z.y - z.z, -z.x + z.y + z.z, z.x - z.y + z.z});
  const double estimate = (planes - 1.0) / std::sqrt(3.0) * std::pow(s, -tetrahedron.iterations) * tetrahedron.size;
  return std::max(glm::length(c) - std::sqrt(3.0) * tetrahedron.size, estimate);
}

double sd_mandelbox(const glm::dvec3& p, const Mandelbox& box) {
  // Orbits past |z| = 1e4 have left the set's cube for good.
  constexpr double kBailout = 1e4;
  const glm::dvec3 c = p - box.center;
  glm::dvec3 z = c;
  double dr = 1.0;
  for (int i = 0; i < box.iterations && glm::length(z) <= kBailout; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      // The box fold: a coordinate beyond +-1 reflected about it.
      if (z[axis] > 1.0) {
        z[axis] = 2.0 - z[axis];
      } else if (z[axis] < -1.0) {
        z[axis] = -2.0 - z[axis];
      }
    }
    const double r = glm::length(z);
    double fold = 1.0;
    if (r < box.min_radius) {
      fold = (box.fixed_radius * box.fixed_radius) / (box.min_radius * box.min_radius);
    } else if (r < box.fixed_radius) {
      fold = (box.fixed_radius * box.fixed_radius) / (r * r);
    }
    z = box.scale * fold * z + c;
    dr = dr * std::abs(box.scale) * fold + 1.0;
  }
  return std::max(glm::length(c) - std::sqrt(3.0) * mandelbox_half_size(box.scale), glm::length(z) / dr);
}

double sd_julia(const glm::dvec3& p, const Julia& julia) {
  constexpr double kBailout = 16.0;
  const glm::dvec3 q = p - julia.center;
  // glm's quaternions are (w, x, y, z) with w the real part.
  glm::dquat z(q.x, q.y, q.z, 0.0);
  const glm::dquat c(julia.c.x, julia.c.y, julia.c.z, julia.c.w);
  double dz = 1.0;
  for (int i = 0; i < julia.iterations && glm::length(z) <= kBailout; ++i) {
    dz *= 2.0 * glm::length(z);
    z = z * z + c;
  }
  // An orbit that stays is on or in the set; one through 0 (at the centre) has dz = 0 and is capped.
  const double r = glm::length(z);
  const double estimate =
      r <= kBailout ? 0.0 : std::min(0.5 * r * std::log(r) / std::max(dz, kTinyRadius), kEstimateCap);
  return std::max(glm::length(q) - julia_radius(julia.c), estimate);
}

double sd_menger(const glm::dvec3& p, const Menger& sponge) {
  const glm::dvec3 q = (p - sponge.center) / sponge.half_size;
  const glm::dvec3 b = glm::abs(q) - 1.0;
  double d = glm::length(glm::max(b, 0.0)) + std::min(std::max(b.x, std::max(b.y, b.z)), 0.0);
  double s = 1.0;
  for (int i = 0; i < sponge.iterations; ++i) {
    // The cell of this level, centred: a in [-1, 1); the cross of half width 1/3 of the cell is
    // where at least two of |1 - 3|a|| exceed 1.
    const glm::dvec3 a(floor_mod(q.x * s, 2.0) - 1.0, floor_mod(q.y * s, 2.0) - 1.0, floor_mod(q.z * s, 2.0) - 1.0);
    s *= 3.0;
    const glm::dvec3 r = glm::abs(1.0 - 3.0 * glm::abs(a));
    const double cross = (std::min({std::max(r.x, r.y), std::max(r.y, r.z), std::max(r.z, r.x)}) - 1.0) / s;
    d = std::max(d, cross);
  }
  return d * sponge.half_size;
}

}  // namespace clmarch

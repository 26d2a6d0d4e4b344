// The reference march, normal estimate and shading in double, and the row-parallel frame loop.
#include "reference/reference_renderer.hpp"

#include "common/progress.hpp"
#include "reference/reference_sdf.hpp"
#include "scene/camera_model.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace clmarch {
namespace {

/// Unit vector along v; a zero vector (a flat spot of the field, opposite light and view) stays
/// zero, as in the kernels, instead of becoming NaN.
glm::dvec3 normalize_or_zero(const glm::dvec3& v) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : glm::dvec3(0.0);
}

glm::dvec3 central_normal(const Node& root, const glm::dvec3& p, double h) {
  const auto f = [&](const glm::dvec3& q) { return reference_distance(root, q); };
  const glm::dvec3 x(h, 0.0, 0.0), y(0.0, h, 0.0), z(0.0, 0.0, h);
  return normalize_or_zero(glm::dvec3(f(p + x) - f(p - x), f(p + y) - f(p - y), f(p + z) - f(p - z)));
}

// Inigo Quilez's four-sample tetrahedron; cheaper than central differences but only first order.
glm::dvec3 tetrahedral_normal(const Node& root, const glm::dvec3& p, double h) {
  const auto f = [&](const glm::dvec3& q) { return reference_distance(root, q); };
  const glm::dvec3 xyy(1.0, -1.0, -1.0), yyx(-1.0, -1.0, 1.0), yxy(-1.0, 1.0, -1.0), xxx(1.0, 1.0, 1.0);
  return normalize_or_zero(xyy * f(p + xyy * h) + yyx * f(p + yyx * h) + yxy * f(p + yxy * h) +
                        xxx * f(p + xxx * h));
}

// Specular factor of one light; only called where n.l > 0.
double specular_term(ShadingModel model, const glm::dvec3& n, const glm::dvec3& l, const glm::dvec3& v,
                     double shininess) {
  switch (model) {
    case ShadingModel::Lambert: return 0.0;
    case ShadingModel::Phong: return std::pow(std::max(glm::dot(glm::reflect(-l, n), v), 0.0), shininess);
    case ShadingModel::BlinnPhong: return std::pow(std::max(glm::dot(n, normalize_or_zero(l + v)), 0.0), shininess);
  }
  return 0.0;
}

}  // namespace

glm::dvec3 reference_normal(const Node& root, const glm::dvec3& p, NormalMethod method, double h) {
  switch (method) {
    case NormalMethod::Central: return central_normal(root, p, h);
    case NormalMethod::Tetrahedral: return tetrahedral_normal(root, p, h);
  }
  return glm::dvec3(0.0);
}

glm::dvec3 reference_shade(const Scene& scene, const glm::dvec3& p, const glm::dvec3& n,
                           const glm::dvec3& direction, int steps) {
  const Shading& sh = scene.shading;
  const glm::dvec3 v = -direction;
  const glm::dvec3 albedo = reference_sample(scene.sdf, p).color;
  glm::dvec3 color = albedo * sh.ambient;
  for (const Light& light : scene.lights) {
    const glm::dvec3 l =
        light.kind == LightKind::Point ? normalize_or_zero(light.position - p) : light.direction;
    const glm::dvec3 radiance = light.color * light.intensity;
    const double ndotl = std::max(glm::dot(n, l), 0.0);
    color += albedo * radiance * (sh.diffuse * ndotl);
    if (ndotl > 0.0) color += radiance * (sh.specular * specular_term(sh.model, n, l, v, sh.shininess));
  }
  if (sh.step_ao > 0.0) color -= static_cast<double>(steps) * steps / sh.step_ao;
  return glm::max(color, 0.0);
}

RayResult reference_trace(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction) {
  const RenderSettings& rs = scene.render;
  RayResult r;
  double t = 0.0;
  for (int i = 0; i < rs.max_steps; ++i) {
    const glm::dvec3 p = origin + t * direction;
    const double d = reference_distance(scene.sdf, p);
    ++r.steps;
    if (d < rs.epsilon) {
      r.hit = true;
      r.depth = t;
      r.normal = reference_normal(scene.sdf, p, rs.normal_method, rs.normal_epsilon);
      r.color = reference_shade(scene, p, r.normal, direction, r.steps);
      return r;
    }
    t += d;
    if (t >= rs.max_distance) break;
  }
  // Running out of steps is a miss too, like leaving through max_distance.
  r.depth = std::numeric_limits<double>::infinity();
  r.color = scene.shading.background;
  return r;
}

FrameBuffers render_reference(const Scene& scene) {
  const int width = scene.render.width;
  const int height = scene.render.height;
  const CameraBasis basis = camera_basis(scene.camera, width, height);
  FrameBuffers fb(width, height);
  ProgressLine progress("reference rows", height);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      for (int i = 0; i < width; ++i) {
        const RayResult r = reference_trace(scene, basis.origin, pixel_ray_direction(basis, i, j));
        fb.at(Channel::R, i, j) = static_cast<float>(r.color.r);
        fb.at(Channel::G, i, j) = static_cast<float>(r.color.g);
        fb.at(Channel::B, i, j) = static_cast<float>(r.color.b);
        fb.at(Channel::Depth, i, j) = static_cast<float>(r.depth);
        fb.at(Channel::Steps, i, j) = static_cast<float>(r.steps);
        fb.at(Channel::NX, i, j) = static_cast<float>(r.normal.x);
        fb.at(Channel::NY, i, j) = static_cast<float>(r.normal.y);
        fb.at(Channel::NZ, i, j) = static_cast<float>(r.normal.z);
      }
      progress.advance();
    }
  });
  return fb;
}

}  // namespace clmarch

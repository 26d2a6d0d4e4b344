// The reference march, normal estimate and shading in double, and the row-parallel frame loop.
#include "reference/reference_renderer.hpp"

#include "common/progress.hpp"
#include "reference/reference_sdf.hpp"
#include "scene/camera_model.hpp"
#include "scene/tiling_model.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace clmarch {
namespace {

/// Unit vector along v; a zero vector (a flat spot of the field, opposite light and view) stays
/// zero, as in the kernels, instead of becoming NaN.
glm::dvec3 normalize_or_zero(const glm::dvec3& v) {
  const double length = glm::length(v);
  return length > 0.0 ? v / length : glm::dvec3(0.0);
}

using Field = std::function<double(const glm::dvec3&)>;

glm::dvec3 central_normal(const Field& f, const glm::dvec3& p, double h) {
  const glm::dvec3 x(h, 0.0, 0.0), y(0.0, h, 0.0), z(0.0, 0.0, h);
  return normalize_or_zero(glm::dvec3(f(p + x) - f(p - x), f(p + y) - f(p - y), f(p + z) - f(p - z)));
}

// Inigo Quilez's four-sample tetrahedron; cheaper than central differences but only first order.
glm::dvec3 tetrahedral_normal(const Field& f, const glm::dvec3& p, double h) {
  const glm::dvec3 xyy(1.0, -1.0, -1.0), yyx(-1.0, -1.0, 1.0), yxy(-1.0, 1.0, -1.0), xxx(1.0, 1.0, 1.0);
  return normalize_or_zero(xyy * f(p + xyy * h) + yyx * f(p + yyx * h) + yxy * f(p + yxy * h) +
                           xxx * f(p + xxx * h));
}

glm::dvec3 normal_of(const Field& f, const glm::dvec3& p, NormalMethod method, double h) {
  switch (method) {
    case NormalMethod::Central: return central_normal(f, p, h);
    case NormalMethod::Tetrahedral: return tetrahedral_normal(f, p, h);
  }
  return glm::dvec3(0.0);
}

/// p wrapped into the tiling cell, floor-based like GLSL mod.
glm::dvec3 wrap_to_cell(const glm::dvec3& p, const glm::dvec3& cell) { return p - cell * glm::floor(p / cell); }

/// Where a march ended: the depth, the point in the tree's own frame, the steps.
struct MarchEnd {
  bool hit = false;
  double depth = 0.0;
  glm::dvec3 local{0.0};
  int steps = 0;
  int wall_steps = 0;
};

MarchEnd march_plain(const Scene& scene, const Field& field, const glm::dvec3& origin, const glm::dvec3& direction) {
  const RenderSettings& rs = scene.render;
  MarchEnd end;
  double t = 0.0;
  for (int i = 0; i < rs.max_steps; ++i) {
    const glm::dvec3 p = origin + t * direction;
    const double d = field(p);
    ++end.steps;
    if (d < rs.epsilon) {
      end.hit = true;
      end.depth = t;
      end.local = p;
      return end;
    }
    t += d;
    if (t >= rs.max_distance) break;
  }
  return end;
}

// The unit-cell traversal: inside the current cell the ray is entry + s * direction; when the
// wall it heads for is no farther along the ray than the surface, it steps exactly onto that wall
// and re-enters the neighbouring cell at the opposite wall (several axes at once at edges and
// corners).
MarchEnd march_cells(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction) {
  const RenderSettings& rs = scene.render;
  const glm::dvec3 cell = scene.tiling->cell;
  MarchEnd end;
  glm::dvec3 entry = offset_in_cell(origin, cell);
  double t_entry = 0.0, s = 0.0;
  for (int i = 0; i < rs.max_steps; ++i) {
    const glm::dvec3 p = entry + s * direction;
    const double d = reference_distance(scene.sdf, p);
    glm::dvec3 wall_axis(std::numeric_limits<double>::infinity());
    for (int a = 0; a < 3; ++a) {
      if (direction[a] == 0.0) continue;
      const double to_wall = direction[a] > 0.0 ? cell[a] - p[a] : -p[a];
      wall_axis[a] = std::max(to_wall / direction[a], 0.0);
    }
    const double wall = std::min({wall_axis.x, wall_axis.y, wall_axis.z});
    ++end.steps;
    if (d < rs.epsilon) {
      end.hit = true;
      end.depth = t_entry + s;
      end.local = p;
      return end;
    }
    if (wall <= d) {
      ++end.wall_steps;
      const glm::dvec3 at_wall = p + wall * direction;
      for (int a = 0; a < 3; ++a) {
        entry[a] = wall_axis[a] == wall ? (direction[a] > 0.0 ? 0.0 : cell[a]) : std::clamp(at_wall[a], 0.0, cell[a]);
      }
      t_entry += s + wall;
      s = 0.0;
    } else {
      s += d;
    }
    if (t_entry + s >= rs.max_distance) break;
  }
  return end;
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
  return normal_of([&](const glm::dvec3& q) { return reference_distance(root, q); }, p, method, h);
}

glm::dvec3 reference_shade(const Scene& scene, const glm::dvec3& p_local, const glm::dvec3& p, const glm::dvec3& n,
                           const glm::dvec3& direction, int steps, double depth) {
  const Shading& sh = scene.shading;
  const glm::dvec3 v = -direction;
  const glm::dvec3 albedo = reference_sample(scene.sdf, p_local).color;
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
  color = glm::max(color, 0.0);
  if (sh.fog) color = sh.fog->color + (color - sh.fog->color) * std::exp(-sh.fog->density * depth);
  return color;
}

RayResult reference_trace(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction) {
  const RenderSettings& rs = scene.render;
  Field field = [&](const glm::dvec3& p) { return reference_distance(scene.sdf, p); };
  MarchEnd end;
  if (!scene.tiling) {
    end = march_plain(scene, field, origin, direction);
  } else if (scene.tiling->method == TilingMethod::Mod) {
    // The sample point wraps into the cell, and so do the normal's taps.
    field = [&](const glm::dvec3& p) { return reference_distance(scene.sdf, wrap_to_cell(p, scene.tiling->cell)); };
    end = march_plain(scene, field, origin, direction);
    end.local = wrap_to_cell(end.local, scene.tiling->cell);
  } else {
    end = march_cells(scene, origin, direction);
  }
  RayResult r;
  r.steps = end.steps;
  r.wall_steps = end.wall_steps;
  if (!end.hit) {
    // Running out of steps is a miss too, like leaving through max_distance.
    r.depth = std::numeric_limits<double>::infinity();
    r.color = scene.shading.background;
    return r;
  }
  r.hit = true;
  r.depth = end.depth;
  r.normal = normal_of(field, end.local, rs.normal_method, rs.normal_epsilon);
  r.color = reference_shade(scene, end.local, origin + end.depth * direction, r.normal, direction, r.steps, end.depth);
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
        fb.at(Channel::WallSteps, i, j) = static_cast<float>(r.wall_steps);
      }
      progress.advance();
    }
  });
  return fb;
}

}  // namespace clmarch

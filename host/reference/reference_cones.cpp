// The cone pass's rule, once more in double: each block's cone holds the rays through its pixel
// centres and steps only as far as no ray of the block could have hit (or glowed) before.
#include "reference/reference_cones.hpp"

#include "device_types.h"
#include "reference/reference_march.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

constexpr int kBlock = CLMARCH_COARSE_BLOCK;
/// The cone stops once its step falls below this fraction of the plain sphere-tracing step.
constexpr double kStopFraction = 0.25;

struct BlockCone {
  glm::dvec3 axis{0.0};
  double spread = 0.0;  ///< bound on |u - axis| over the block's unit rays u
};

BlockCone block_cone(const CameraBasis& basis, int x0, int y0, int x1, int y1) {
  // Pixel centres at i + 0.5; the block's rays form a convex patch of the image plane, and the
  // angle to the axis is quasi-convex there, so a corner ray is the farthest.
  BlockCone cone;
  cone.axis = camera_ray_direction(basis, 0.5 * (x0 + x1) + 0.5, 0.5 * (y0 + y1) + 0.5);
  double chord = 0.0;
  for (int x : {x0, x1}) {
    for (int y : {y0, y1})
      chord = std::max(chord, glm::length(camera_ray_direction(basis, x + 0.5, y + 0.5) - cone.axis));
  }
  // The same growth as the kernel's, which covers its float directions.
  cone.spread = chord * 1.001 + 1e-6;
  return cone;
}

}  // namespace

double ConeStarts::at_pixel(int i, int j) const {
  return start[static_cast<std::size_t>(j / kBlock) * blocks_x + static_cast<std::size_t>(i / kBlock)];
}

ConeStarts reference_cone_starts(const Scene& scene) {
  const int width = scene.render.width, height = scene.render.height;
  const CameraBasis basis = camera_basis(scene.camera, width, height);
  const Field field = scene_field(scene);
  const MarchLimits limits = camera_march_limits(scene);
  const double margin = scene.shading.glow ? scene.shading.glow->radius : 0.0;
  double t_first = 0.0, t_last = scene.render.max_distance;
  if (const std::optional<BoundingSphere> bounds = camera_ray_bounds(scene)) {
    const double distance = glm::length(scene.camera.position - bounds->center);
    t_first = std::max(distance - bounds->radius, 0.0);
    t_last = std::min(distance + bounds->radius, t_last);
  }
  ConeStarts cones;
  cones.blocks_x = CLMARCH_COARSE_BLOCKS(width);
  const int blocks_y = CLMARCH_COARSE_BLOCKS(height);
  cones.start.assign(static_cast<std::size_t>(cones.blocks_x) * blocks_y, t_first);
  cones.steps.assign(cones.start.size(), 0);
  tbb::parallel_for(0, static_cast<int>(cones.start.size()), [&](int b) {
    const int x0 = (b % cones.blocks_x) * kBlock, y0 = (b / cones.blocks_x) * kBlock;
    const BlockCone cone =
        block_cone(basis, x0, y0, std::min(x0 + kBlock, width) - 1, std::min(y0 + kBlock, height) - 1);
    const double k = cone.spread, slope = limits.hit_cone_slope;
    double t = t_first;
    int steps = 0;
    while (t < t_last && steps < limits.max_steps) {
      const double d = field(scene.camera.position + t * cone.axis);
      ++steps;
      // Each ray's field up to depth t + s stays >= d - k (t + s) - s; keep it above the hit
      // threshold there, max(epsilon, slope (t + s)), plus the glow radius.
      const double s = std::min((d - limits.epsilon - margin - k * t) / (1.0 + k),
                                (d - margin - (k + slope) * t) / (1.0 + k + slope));
      if (!(s >= kStopFraction * d)) break;
      t = std::min(t + s, t_last);
    }
    cones.start[static_cast<std::size_t>(b)] = t;
    cones.steps[static_cast<std::size_t>(b)] = steps;
  });
  return cones;
}

std::optional<ConeStarts> reference_cones_if_used(const Scene& scene) {
  return uses_cone_pass(scene) ? std::optional(reference_cone_starts(scene)) : std::nullopt;
}

}  // namespace clmarch

// The reference's march loops in double: plain sphere tracing (also under the mod tiling, with a
// wrapping field) and the unit-cell traversal of the cells tiling. Camera, reflection and shadow
// rays all use them, with the rules of docs/scene-format.md.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <functional>
#include <limits>

namespace clmarch {

/// The distance field as the march sees it, in the frame map() is written in.
using Field = std::function<double(const glm::dvec3&)>;

/// The field of the scene: the tree, wrapped into the cell first under the mod tiling.
Field scene_field(const Scene& scene);

struct MarchLimits {
  int max_steps = 255;
  double epsilon = 1e-4;
  /// Shadow rays: 0 no penumbra, 1 Inigo Quilez's min(k h / t), 2 his improved variant.
  int soft_mode = 0;
  double soft_k = 0.0;
  /// Keinert et al.'s omega: steps of omega * d, with the safe fall-back; 1 = plain (camera rays only).
  double over_relaxation = 1.0;
  /// A ray at depth t arrives below max(epsilon, hit_cone_slope * t) (camera rays only).
  double hit_cone_slope = 0.0;
};

/// The limits of camera rays: the render settings' budget, threshold and over-relaxation.
MarchLimits camera_march_limits(const Scene& scene);

/// Where a march ended.
struct MarchEnd {
  bool hit = false;
  double depth = 0.0;
  /// The last point, in the frame of the tree (a cell's frame under tiling).
  glm::dvec3 local{0.0};
  int steps = 0;
  int wall_steps = 0;
  /// Whether the step budget stopped the march: neither a hit nor past t_end.
  bool exhausted = false;
  /// Smallest distance met on the way.
  double closest = std::numeric_limits<double>::infinity();
  /// Soft shadows: light reaching the start, 1 when unoccluded.
  double penumbra = 1.0;
};

/// Marches origin + t * direction (origin in the tree's frame) for t from t_start until a hit, t
/// reaching t_end, or the step budget; under the cells tiling with the unit-cell traversal.
MarchEnd reference_march(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction, double t_start,
                         double t_end, const MarchLimits& limits);

/// Where the camera's rays start: the camera position, or its offset in its cell under the cells tiling.
glm::dvec3 camera_origin_in_frame(const Scene& scene);

}  // namespace clmarch

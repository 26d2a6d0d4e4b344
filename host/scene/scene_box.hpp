// Axis-aligned bounding boxes of the SDF tree: tighter than the bounding spheres where a shape is
// boxy (a box, the Menger sponge, a union of them), so rays march only where the sphere and the box
// both allow (render.bounds: box, the default; docs/scene-format.md#bounding-sphere). One
// definition, used by the OpenCL renderer and the CPU reference alike.
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_bounds.hpp"

#include <optional>

namespace clmarch {

/// Where a node's field can fall below a threshold tau: only inside [low, high] grown by gain * tau
/// on every side (in the node's parent frame).
struct BoundingBox {
  glm::dvec3 low{0.0};
  glm::dvec3 high{0.0};
  double gain = 1.0;
};

/// The box of node's field: its bounding sphere's cube, narrowed where the kind knows better (box,
/// round_box, box_frame, torus, menger) and through unions, intersections and subtractions;
/// nothing for unbounded fields.
std::optional<BoundingBox> node_box(const Node& node);

/// The box camera, shadow and mirror rays are clipped to besides the sphere: the tree's box grown
/// as camera_ray_bounds grows the sphere. Nothing unless render.bounds is box (the default), and
/// for unbounded trees, tiled scenes and scenes with step-count occlusion (shading.step_ao).
std::optional<BoundingBox> camera_ray_box(const Scene& scene);

/// The part [t_enter, t_exit] of the ray origin + t dir inside box, by its slabs; a ray parallel to
/// a slab it starts outside of gets t_enter = +inf, t_exit = -inf (t_enter > t_exit: it misses).
RaySpan ray_box_span(const glm::dvec3& origin, const glm::dvec3& dir, const BoundingBox& box);

}  // namespace clmarch

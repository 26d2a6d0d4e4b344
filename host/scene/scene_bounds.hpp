// The bounding sphere of a scene: camera rays are clipped to it, so rays that miss it cost no
// distance evaluation and rays that pass through stop where they leave it. One definition, used by
// the OpenCL renderer and the CPU reference alike (the march rule in docs/scene-format.md).
#pragma once

#include "scene/scene.hpp"

#include <optional>

namespace clmarch {

/// Where a node's field can fall below a threshold tau: only inside the sphere of radius
/// radius + gain * tau around center (in the node's parent frame). gain grows where the field is
/// scaled down (step_factor, displacement's Lipschitz divisor).
struct BoundingSphere {
  glm::dvec3 center{0.0};
  double radius = 0.0;
  double gain = 1.0;
};

/// The smallest sphere holding both spheres (their thresholds counted with the larger gain).
BoundingSphere enclosing(const BoundingSphere& a, const BoundingSphere& b);

/// The bound of node's field; nothing for unbounded fields (plane, terrain, repeat).
std::optional<BoundingSphere> node_bounds(const Node& node);
/// The same in the node's own frame, before its transform, step_factor and scale.
std::optional<BoundingSphere> local_bounds(const Node& node);

/// How far from the axis (0: x, 1: y, 2: z) through the origin the child's surface reaches: the
/// twist's (y) and bend's (z) reach, which their Lipschitz factors take.
double turn_reach(const BoundingSphere& child, int axis);
/// The sphere holding child turned about that axis by any angles: centred on the axis at the
/// child's height along it, radius hypot(turn_reach, child radius).
BoundingSphere turned_bounds(const BoundingSphere& child, int axis);

/// How far past a shape's surface the rays' hits and glow reach: the largest hit threshold along a
/// camera ray (epsilon, or the pixel cone at max_distance) and the glow radius. Bounds that rays are
/// clipped to grow by it, times their gain.
double hit_growth(const Scene& scene);

/// The sphere camera rays are clipped to: the tree's bound grown by the largest threshold a camera
/// ray can hit with, the glow radius (misses near the surface glow) and a margin for float rounding.
/// Nothing when render.bounds is none, the tree is unbounded, or the scene is tiled. Shadow and
/// mirror rays march inside it too.
std::optional<BoundingSphere> camera_ray_bounds(const Scene& scene);

/// Under the cells tiling, the sphere in the cell's frame holding the cell's content (the tree's
/// bound, grown as camera_ray_bounds grows it): the march takes the stretch of a cell before the
/// ray meets it in one step (docs/scene-format.md, render.bounds). Nothing when render.bounds is
/// none, the tree is unbounded, or the scene has no cells tiling.
std::optional<BoundingSphere> cell_bounds(const Scene& scene);

/// Whether camera rays start where their block's cone stopped (render.coarse_pass: cone; the
/// loader refuses it with the cells tiling, whose march keeps to one cell at a time).
bool uses_cone_pass(const Scene& scene);

/// scene.render with its automatic choices made (coarse_pass and over_relaxation as the march
/// runs them): two scenes march alike when these are equal.
RenderSettings resolved_render_settings(const Scene& scene);

/// The part [t_enter, t_exit] of the ray origin + t dir (dir unit) inside sphere; nothing if the
/// ray's line misses it. t_enter may be negative (origin inside).
struct RaySpan {
  double t_enter = 0.0;
  double t_exit = 0.0;
};
std::optional<RaySpan> ray_sphere_span(const glm::dvec3& origin, const glm::dvec3& dir, const BoundingSphere& sphere);

}  // namespace clmarch

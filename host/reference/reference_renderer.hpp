// CPU reference renderer: sphere traces the scene IR in double with the march, normal and shading
// rules of the OpenCL renderer (docs/scene-format.md), so the two can be compared pixel by pixel.
#pragma once

#include "frame/frame_buffers.hpp"
#include "reference/reference_cones.hpp"
#include "reference/reference_shading.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <optional>

namespace clmarch {

/// What one ray of the reference march found.
struct RayResult {
  bool hit = false;
  /// Ray parameter of the hit point (the last march point); +inf on a miss.
  double depth = 0.0;
  /// Iterations of the march (distance steps and, under tiling, wall steps); normals and shading
  /// are not counted.
  int steps = 0;
  /// The iterations that stepped to a tiling cell's wall.
  int wall_steps = 0;
  /// How the ray ended (the status channel).
  RayStatus status = RayStatus::Miss;
  /// Estimated unit normal at the hit; 0 on a miss.
  glm::dvec3 normal{0.0};
  /// The number of the primitive hit (the id channel; scene/scene.hpp, primitive_count).
  int primitive = 0;
  /// Final linear color (shaded, with bounces, fog and tone mapping); the sky's on a miss.
  glm::dvec3 color{0.0};
  /// The terms of the hit's lit color as they reach the camera through the fog (the layers); 0
  /// on a miss.
  LightTerms layers;
};

/// Normal at p from finite differences of the field with step h.
glm::dvec3 reference_normal(const Node& root, const glm::dvec3& p, NormalMethod method, double h);

/// Marches from the world point origin along the unit direction, then shades the hit (with
/// bounces, fog and tone mapping) or colors the miss. Under the cells tiling origin must be the
/// camera position plus any offset, as the march starts in the camera's cell.
RayResult reference_trace(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction);

/// Renders scene.render.width x height through the camera contract (camera_model.hpp), rows in
/// parallel, with a progress line on a terminal. Always fills the shaded color; other views are
/// derived from the buffers elsewhere.
FrameBuffers render_reference(const Scene& scene);
/// The same with the cone pass's starts already computed (reference_cones_if_used), for callers
/// that also report the cones' steps.
FrameBuffers render_reference(const Scene& scene, const std::optional<ConeStarts>& cones);

/// The reference's color of another render's hits: for each pixel that render hit, the color the
/// reference gives a surface at that render's depth, with its normal and step count (its other
/// channels are copied). Comparing the two colors leaves out the geometry and tests the shading.
FrameBuffers reshade_hits(const Scene& scene, const FrameBuffers& render);

}  // namespace clmarch

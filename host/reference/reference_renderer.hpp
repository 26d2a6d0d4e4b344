// CPU reference renderer: sphere traces the scene IR in double with the march, normal and shading
// rules of the OpenCL renderer (docs/scene-format.md), so the two can be compared pixel by pixel.
#pragma once

#include "render/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

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
  /// Estimated unit normal at the hit; 0 on a miss.
  glm::dvec3 normal{0.0};
  /// Shaded linear color; shading.background on a miss.
  glm::dvec3 color{0.0};
};

/// Normal at p from finite differences of the field with step h.
glm::dvec3 reference_normal(const Node& root, const glm::dvec3& p, NormalMethod method, double h);

/// Shaded color of a hit with unit normal n: p_local in the frame of the tree (for the albedo; a
/// cell's frame under tiling), p its world position (for the lights), reached along the unit
/// direction after `steps` iterations (they feed the step-count occlusion) at depth (for fog).
glm::dvec3 reference_shade(const Scene& scene, const glm::dvec3& p_local, const glm::dvec3& p, const glm::dvec3& n,
                           const glm::dvec3& direction, int steps, double depth);

/// Marches from origin along the unit direction, then shades the hit.
RayResult reference_trace(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction);

/// Renders scene.render.width x height through the camera contract (camera_model.hpp), rows in
/// parallel, with a progress line on a terminal. Always fills the shaded color; other views are
/// derived from the buffers elsewhere.
FrameBuffers render_reference(const Scene& scene);

}  // namespace clmarch

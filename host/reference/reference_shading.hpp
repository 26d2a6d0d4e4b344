// The reference's lighting and atmosphere in double, by the formulas of docs/scene-format.md:
// the shading models with shadows and occlusion, the sky and glows of misses, fog, tone mapping.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

namespace clmarch {

/// A surface point met by a ray.
struct SurfacePoint {
  /// In the frame of the tree (a cell's frame under tiling): for the field.
  glm::dvec3 local{0.0};
  /// In the world: for the lights.
  glm::dvec3 world{0.0};
  glm::dvec3 normal{0.0};
  Material material;
  /// The number of the primitive whose material it is (the id channel).
  int primitive = 0;
  /// Iterations of the march that found it (step-count occlusion).
  int steps = 0;
};

/// Unit vector along v; a zero vector stays zero (as in the kernels) instead of becoming NaN.
glm::dvec3 normalize_or_zero(const glm::dvec3& v);

/// The share of a light's radiance that reaches a point distance away in direction l (unit,
/// towards the light): 1 / distance^2 with the inverse-square falloff, times the range's window
/// clamp(1 - (distance / range)^4, 0, 1)^2, times a spot light's cone, smoothstep from the cosine
/// of its outer angle (0) to its inner one's (1), a step where they are equal. 1 for directional
/// lights.
double light_reach(const Light& light, const glm::dvec3& l, double distance);

/// The terms of a hit's lit color (the --buffers layers ao, diffuse and specular): the ambient
/// light the occlusion leaves, and the lights' diffuse and specular reflection with their shadows.
struct LightTerms {
  glm::dvec3 ambient{0.0};
  glm::dvec3 diffuse{0.0};
  glm::dvec3 specular{0.0};
};

/// The terms of the lit color at a surface point seen along the unit direction.
LightTerms reference_light_terms(const Scene& scene, const SurfacePoint& surface, const glm::dvec3& direction);
/// Their sum, darkened by the step count of the march that found the point, clamped at 0.
glm::dvec3 reference_lit_color(const Scene& scene, const LightTerms& terms, int steps);
/// Direct light, ambient and occlusion at a surface point seen along the unit direction, clamped at 0.
glm::dvec3 reference_shade(const Scene& scene, const SurfacePoint& surface, const glm::dvec3& direction);

/// The color of a miss along the unit direction whose march came within closest of the surface.
glm::dvec3 reference_miss_color(const Scene& scene, const glm::dvec3& direction, double closest);

/// Fog over depth along the unit direction from the camera.
glm::dvec3 reference_fog(const Scene& scene, const glm::dvec3& color, const glm::dvec3& direction, double depth);

/// Tone mapping and display gamma.
glm::dvec3 reference_tone_map(const Scene& scene, const glm::dvec3& color);

}  // namespace clmarch

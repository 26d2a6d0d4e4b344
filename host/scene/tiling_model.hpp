// Shared definitions of the tiling (docs/tiling.md): the floor-based mod of repetition, and where
// the camera sits inside its cell. Both renderers start their cell traversal from this offset.
#pragma once

#include <glm/glm.hpp>

#include <cmath>

namespace clmarch {

/// GLSL's floor-based mod, x - period floor(x / period), in [0, period) up to rounding
/// (std::fmod truncates towards zero, which mirrors negative coordinates).
inline double floor_mod(double x, double period) { return x - period * std::floor(x / period); }
inline glm::dvec3 floor_mod(const glm::dvec3& p, const glm::dvec3& period) {
  return p - period * glm::floor(p / period);
}

/// position minus the corner of its cell, each component in [0, cell), in double so that the
/// offset stays exact however far the camera is from the origin.
glm::dvec3 offset_in_cell(const glm::dvec3& position, const glm::dvec3& cell);

}  // namespace clmarch

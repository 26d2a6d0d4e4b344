// Shared definitions of the tiling (docs/tiling.md): where the camera sits inside its cell. Both
// renderers start their cell traversal from this offset.
#pragma once

#include <glm/glm.hpp>

namespace clmarch {

/// position minus the corner of its cell, each component in [0, cell), in double so that the
/// offset stays exact however far the camera is from the origin.
glm::dvec3 offset_in_cell(const glm::dvec3& position, const glm::dvec3& cell);

}  // namespace clmarch

// The reference's color patterns (host/scene/scene.hpp, ColorPattern), in double.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

namespace clmarch {

/// pattern's color at q, the point in the frame of the node that sets it.
glm::dvec3 reference_pattern_color(const ColorPattern& pattern, const glm::dvec3& q);

}  // namespace clmarch

// Turns a scene's SDF tree into OpenCL C: map(p), the distance, and map_color(p, &albedo), the
// distance with the blended albedo, calling the functions of kernels/primitives.cl and operators.cl.
#pragma once

#include "scene/scene.hpp"

#include <string>

namespace clmarch {

/// Source of the two functions map and map_color for this tree.
std::string generate_sdf_functions(const Node& root);

}  // namespace clmarch

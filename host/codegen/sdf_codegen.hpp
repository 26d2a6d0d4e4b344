// Turns a scene's SDF tree into OpenCL C: map(p), the distance, and map_color(p, &albedo), the
// distance with the blended albedo, calling the functions of kernels/primitives.cl and operators.cl.
#pragma once

#include "scene/scene.hpp"

#include <string>

namespace clmarch {

/// Source of the two functions map and map_color for this tree, taking points relative to the
/// world point frame_origin (its positions are baked relative to it, in double). With
/// gate_subtrees, unions and subtractions evaluate an expensive bounded subtree only where its
/// bounding sphere shows it can change their result (render.subtree_bounds).
std::string generate_sdf_functions(const Node& root, const glm::dvec3& frame_origin = glm::dvec3(0.0),
                                   bool gate_subtrees = true);

}  // namespace clmarch

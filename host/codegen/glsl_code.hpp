// The program-scope code of a tree's glsl nodes: each distinct program's OpenCL translation, in
// float and in double (the kernel's DOUBLE_PRECISION picks one), and the functions that run it
// on a packet's lanes.
#pragma once

#include "scene/scene.hpp"

#include <string>

namespace clmarch {

/// The functions of the tree's glsl programs, each once: <name>_distance_lanes(vec3v p, real t)
/// and, with a colour function, <name>_color_lanes(vec3v p, real t), for the calls emit_primitive
/// writes. Empty for a tree without glsl nodes.
std::string glsl_functions(const Node& root);

}  // namespace clmarch

// OpenCL C for a color pattern (host/scene/scene.hpp, ColorPattern) at a point: the calls of
// kernels/patterns.cl, or a color expression's tree spelled out.
#pragma once

#include "codegen/sdf_codegen.hpp"
#include "scene/scene.hpp"

#include <string>

namespace clmarch {

/// A vec3v expression of pattern's color at q (a vec3v variable, the point in the frame of the
/// node that sets the pattern), its numbers written to lit.
std::string pattern_color_code(const ColorPattern& pattern, const std::string& q, Literals& lit);

}  // namespace clmarch

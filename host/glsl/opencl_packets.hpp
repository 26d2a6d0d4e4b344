// User GLSL as packet code: every float of the user's functions becomes a lane vector (vfloat) and
// every vector and matrix its components as such vectors, so a packet of LANES points runs the
// user's code as SIMD, as built-in kinds do, instead of one lane at a time. Control flow must be
// the same on every lane: ints and bools may not depend on the point (loop counters, #defines and
// iTime may), and a choice that does is a ?: with no side effects (select()). Code outside that
// subset (an `if` on the distance, an int cell id of the point, structs, arrays, written globals,
// run-time indices) keeps the lane-at-a-time path, with the reason said in the generated code.
#pragma once

#include "glsl/glsl_ir.hpp"
#include "glsl/opencl_translation.hpp"

#include <string>

namespace clmarch::glsl {

/// The packet translation of a module, or why it has none.
struct PacketTranslation {
  /// OpenCL C for programs with LANES > 1 (it uses kernels/lanes.cl's vfloat, vint, real and vec3v):
  ///   vfloat <prefix>_distance_packet(vfloat x, vfloat y, vfloat z, real t)
  ///   vec3v <prefix>_color_packet(vfloat x, vfloat y, vfloat z, real t)   with a colour function
  /// Empty when `obstacle` is set.
  std::string code;
  /// What keeps the module off packets, naming the construct and its line ("line 4: an if whose
  /// condition depends on the point"); empty when `code` is set.
  std::string obstacle;
};

/// The module's distance (and colour) functions as packet code, with GLSL's semantics as
/// translate_to_opencl has them (floor-based mod, x (1 - a) + y a mix, v * m = transpose(m) v,
/// column-major matrices, zero-initialised locals, out and inout arguments written back in order).
PacketTranslation translate_to_packets(const Module& module, const TranslationOptions& options);

}  // namespace clmarch::glsl

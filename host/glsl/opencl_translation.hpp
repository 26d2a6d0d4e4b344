// The IR of user GLSL as OpenCL C, with GLSL's semantics: floor-based mod, vector x matrix as
// transpose(m) x v, column-major matrices, out and inout arguments (swizzles too) through
// temporaries written back on return, zero-initialised locals, wrapping integer arithmetic, user
// names kept apart from OpenCL C's. The code is readable and #line points at the user's file.
#pragma once

#include "glsl/glsl_ir.hpp"
#include "glsl/glsl_uniforms.hpp"

#include <string>

namespace clmarch::glsl {

/// How to translate.
struct TranslationOptions {
  /// Prefix of every name the translation defines at program scope ("glsl0"), unique per node.
  std::string prefix = "glsl0";
  /// GLSL's float as OpenCL's double (render.precision: double); otherwise float.
  bool double_precision = false;
  UniformValues uniforms;
};

/// OpenCL C source defining, after the user's functions (all static-free program-scope functions
/// named with the prefix):
///   real <prefix>_distance(real3 p, real t)   the distance function's distance at p, time t
///   real3 <prefix>_color(real3 p, real t)     the colour function, when the module has one
/// where real is float or double as options say, spelled as such (float3, double3: the kernels
/// typedef no real2 or real3), so the source needs nothing before it but cl_khr_fp64 for double.
/// User names get a trailing underscore (locals, parameters, struct members) or the prefix
/// (functions, types, helpers); GLSL's built-ins that kernels/lanes.cl redefines as macros for one
/// lane of double (pow, atan2, step) are called as (name)(...).
std::string translate_to_opencl(const Module& module, const TranslationOptions& options);

}  // namespace clmarch::glsl

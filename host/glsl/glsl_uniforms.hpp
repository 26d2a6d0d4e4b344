// The values of the shader's uniforms (iTime, iResolution, iFrame, iMouse, iTimeDelta), shared by
// the OpenCL translation and the interpreter so that both read the same numbers.
#pragma once

#include <cmath>

namespace clmarch::glsl {

/// What the uniforms hold besides time, which each evaluation passes.
struct UniformValues {
  /// iResolution.xy: the render's width and height; .z is 1.
  double resolution_x = 640.0;
  double resolution_y = 360.0;
};

/// Frames a second behind iFrame and iTimeDelta (Shadertoy's nominal rate).
inline constexpr double kFramesPerSecond = 60.0;

/// iFrame at time t.
inline int frame_at(double time) { return static_cast<int>(std::floor(time * kFramesPerSecond)); }

}  // namespace clmarch::glsl

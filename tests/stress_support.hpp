// Shared by the numerical-stability stress tests (issue 7): the invariants every render must keep
// whatever the input (finite buffers, +inf depth only on misses, steps within the budget) and
// bitwise run-to-run comparison.
#pragma once

#include "frame/frame_buffers.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <string>

namespace clmarch::stress {

// Float unit roundoff u = 2^-24 (docs/accuracy.md).
inline constexpr double kUnitRoundoff = 0x1p-24;
// Float rounding of o + t*d, of the direction and of the distance evaluation: ~16 u of the
// coordinates' magnitude (the rounding term of docs/accuracy.md's depth tolerance).
inline constexpr double kFloatRelative = 16.0 * kUnitRoundoff;
// Below this |cos| between ray and surface a ray grazes: its depth bound epsilon / cos blows up and
// it may legitimately run out of steps, so it counts with the silhouette.
inline constexpr double kGrazingCosine = 0.1;

/// The first pixel that breaks an invariant of the buffers, described; empty when all hold:
/// color, normal and steps finite; depth finite and >= 0 on a hit, +inf on a miss; steps an
/// integer in [0, max_steps] (0 only on a miss: a ray outside the scene's bounding sphere is not
/// marched), wall steps in [0, steps]; the normal 0 on a miss and unit length or 0
/// (a zero gradient, e.g. at a sphere's centre) on a hit. shaded: the color planes were written.
std::string invariant_violation(const FrameBuffers& buffers, int max_steps, bool shaded);

/// Renders scene on the OpenCL device.
FrameBuffers render(const Scene& scene, KernelPurpose purpose = KernelPurpose::Shaded, int lanes = 16);

/// Renders twice and returns the first render; fails the current test if any plane differs in
/// any bit between the runs or an invariant is broken, also in a render in the other precision.
FrameBuffers render_checked(const Scene& scene, KernelPurpose purpose = KernelPurpose::Shaded, int lanes = 16);

/// True when every plane of a and b is bitwise equal.
bool bitwise_equal(const FrameBuffers& a, const FrameBuffers& b);

/// The pixel's unit ray direction by the camera contract, in double.
glm::dvec3 ray_direction(const Scene& scene, int i, int j);

/// True when sweeps (every offset, every axis) were asked for with CLMARCH_STRESS_SWEEP=1.
bool sweep_requested();

}  // namespace clmarch::stress

// Tolerances several test files share, each with its reason: one definition, so that the files can
// be compiled together in one unity batch (tests/CMakeLists.txt).
#pragma once

namespace clmarch::testing {

/// Float rounding of o + t*d, of the direction and of the distance evaluation: ~16 ulps of the
/// coordinates' magnitude (docs/accuracy.md).
inline constexpr double kFloatRelative = 16.0 * 0x1p-24;

/// Rays closer than this to tangent (|cos| between ray and surface normal) graze the surface: the
/// depth bound threshold / cos blows up, and the march may legitimately run out of steps there.
inline constexpr double kGrazingCosine = 0.1;

/// Closed forms of a handful of double operations on O(1) values: anything looser is a bug.
inline constexpr double kExact = 1e-12;

}  // namespace clmarch::testing

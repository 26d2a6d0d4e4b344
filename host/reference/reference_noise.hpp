// Reference lattice noise and terrain heights in double: an integer hash of the lattice point (the
// same uint32 arithmetic as kernels/noise.cl, so both see the same lattice values), value noise
// with its analytic gradient, gradient (Perlin) noise, and the three fractal sums of a terrain.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>

namespace clmarch {

/// The lattice cell of a coordinate: floor(x) as an int32, saturated at the int32 limits (NaN: 0),
/// like OpenCL's convert_int_sat.
std::int32_t noise_lattice(double x);

/// 32 mixed bits of the lattice point (ix, iz) under seed, with uint32 wrap-around.
std::uint32_t noise_hash(std::uint32_t ix, std::uint32_t iz, std::uint32_t seed);

/// The hash as a lattice value in [0, 1): its top 24 bits times 2^-24 (exact in float too).
double noise_hash01(std::uint32_t ix, std::uint32_t iz, std::uint32_t seed);

/// A noise value with its gradient d/dx, d/dz.
struct NoiseSample {
  double value;
  glm::dvec2 gradient;
};

/// Value noise at (x, z): the lattice values blended by the cubic smoothstep 3f^2 - 2f^3, in [0, 1),
/// with its analytic gradient (Inigo Quilez's noised).
NoiseSample value_noise(const glm::dvec2& q, std::uint32_t seed);

/// Gradient (Perlin) noise at (x, z): lattice gradients with components in [-1, 1) from the hash,
/// blended by the quintic 6f^5 - 15f^4 + 10f^3; zero on every lattice point.
double perlin_noise(const glm::dvec2& q, std::uint32_t seed);

/// The terrain's surface height at (x, z) = (xz.x, xz.y).
double terrain_height(const glm::dvec2& xz, const Terrain& terrain);

/// p.y - terrain_height(p.xz): exact for a flat terrain, a bound only after a step factor
/// 1 / sqrt(1 + slope^2) otherwise.
double sd_terrain(const glm::dvec3& p, const Terrain& terrain);

}  // namespace clmarch

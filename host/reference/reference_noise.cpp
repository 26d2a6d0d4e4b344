// Reference noise and terrain in double (formulas: docs/scene-format.md, "Fractals and terrain").
#include "reference/reference_noise.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace clmarch {
namespace {

// Octave to octave, the sample point turns by the rotation (0.8, 0.6; -0.6, 0.8) (36.87 degrees,
// Inigo Quilez's m2) so the lattices of successive octaves do not line up, and is scaled.
glm::dvec2 next_octave(const glm::dvec2& q, double lacunarity) {
  return lacunarity * glm::dvec2(0.8 * q.x + 0.6 * q.y, -0.6 * q.x + 0.8 * q.y);
}

// The lattice gradient of perlin_noise: two 16-bit halves of the hash, each scaled to [-1, 1).
glm::dvec2 lattice_gradient(std::uint32_t ix, std::uint32_t iz, std::uint32_t seed) {
  const std::uint32_t h = noise_hash(ix, iz, seed);
  return {static_cast<double>(h & 0xffffu) * 0x1p-15 - 1.0, static_cast<double>(h >> 16) * 0x1p-15 - 1.0};
}

// The fractal sum of value or Perlin noise: octave i has weight 0.5^i and frequency 2^i.
template <class Noise>
double fbm(glm::dvec2 q, int octaves, Noise noise) {
  double sum = 0.0, weight = 1.0;
  for (int i = 0; i < octaves; ++i) {
    sum += weight * noise(q);
    weight *= 0.5;
    q = next_octave(q, 2.0);
  }
  return sum;
}

// The noise-derivative sum of Heckel's article (after Inigo Quilez): each octave's value is damped
// by the slope accumulated so far, 1 / (1 + |sum of gradients|^2), so slopes stay smooth and
// flats get detail; the weight starts at 2.5 and flips sign as it shrinks (x -0.4), the sum is
// damped by 0.85 per octave and the frequency grows 2.75 times.
double derivative_fbm(glm::dvec2 q, int octaves, std::uint32_t seed) {
  double sum = 0.0, weight = 2.5;
  glm::dvec2 slope(0.0);
  for (int i = 0; i < octaves; ++i) {
    const NoiseSample n = value_noise(q, seed);
    slope += n.gradient;
    sum += weight * n.value / (1.0 + glm::dot(slope, slope));
    weight *= -0.4;
    sum *= 0.85;
    q = next_octave(q, 2.75);
  }
  return sum;
}

}  // namespace

std::int32_t noise_lattice(double x) {
  const double cell = std::floor(x);
  if (std::isnan(cell)) return 0;
  if (cell >= 2147483647.0) return std::numeric_limits<std::int32_t>::max();
  if (cell <= -2147483648.0) return std::numeric_limits<std::int32_t>::min();
  return static_cast<std::int32_t>(cell);
}

std::uint32_t noise_hash(std::uint32_t ix, std::uint32_t iz, std::uint32_t seed) {
  // Spatial-hash primes on each coordinate, then Chris Wellons' lowbias32 finaliser. All uint32:
  // products and shifts wrap exactly as OpenCL's uint does.
  std::uint32_t h = (ix * 0x8da6b343u) ^ (iz * 0xd8163841u) ^ ((seed + 0x9e3779b9u) * 0xcb1ab31fu);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

double noise_hash01(std::uint32_t ix, std::uint32_t iz, std::uint32_t seed) {
  return static_cast<double>(noise_hash(ix, iz, seed) >> 8) * 0x1p-24;
}

NoiseSample value_noise(const glm::dvec2& q, std::uint32_t seed) {
  const std::uint32_t ix = static_cast<std::uint32_t>(noise_lattice(q.x));
  const std::uint32_t iz = static_cast<std::uint32_t>(noise_lattice(q.y));
  const glm::dvec2 f = q - glm::floor(q);
  const glm::dvec2 u = f * f * (3.0 - 2.0 * f);
  const glm::dvec2 du = 6.0 * f * (1.0 - f);
  const double a = noise_hash01(ix, iz, seed);
  const double b = noise_hash01(ix + 1u, iz, seed);
  const double c = noise_hash01(ix, iz + 1u, seed);
  const double d = noise_hash01(ix + 1u, iz + 1u, seed);
  const double k = a - b - c + d;
  return {a + (b - a) * u.x + (c - a) * u.y + k * u.x * u.y, du * glm::dvec2((b - a) + k * u.y, (c - a) + k * u.x)};
}

double perlin_noise(const glm::dvec2& q, std::uint32_t seed) {
  const std::uint32_t ix = static_cast<std::uint32_t>(noise_lattice(q.x));
  const std::uint32_t iz = static_cast<std::uint32_t>(noise_lattice(q.y));
  const glm::dvec2 f = q - glm::floor(q);
  const glm::dvec2 u = f * f * f * (f * (6.0 * f - 15.0) + 10.0);
  const double a = glm::dot(lattice_gradient(ix, iz, seed), f);
  const double b = glm::dot(lattice_gradient(ix + 1u, iz, seed), f - glm::dvec2(1.0, 0.0));
  const double c = glm::dot(lattice_gradient(ix, iz + 1u, seed), f - glm::dvec2(0.0, 1.0));
  const double d = glm::dot(lattice_gradient(ix + 1u, iz + 1u, seed), f - glm::dvec2(1.0, 1.0));
  return a + (b - a) * u.x + (c - a) * u.y + (a - b - c + d) * u.x * u.y;
}

double terrain_height(const glm::dvec2& xz, const Terrain& terrain) {
  const glm::dvec2 q = terrain.frequency * xz;
  const std::uint32_t seed = terrain.seed;
  double sum = 0.0;
  switch (terrain.noise) {
    case TerrainNoise::Value:
      sum = fbm(q, terrain.octaves, [seed](const glm::dvec2& x) { return value_noise(x, seed).value; });
      break;
    case TerrainNoise::Perlin:
      sum = fbm(q, terrain.octaves, [seed](const glm::dvec2& x) { return perlin_noise(x, seed); });
      break;
    case TerrainNoise::Derivative:
      sum = derivative_fbm(q, terrain.octaves, seed);
      break;
  }
  return terrain.height + terrain.amplitude * sum;
}

double sd_terrain(const glm::dvec3& p, const Terrain& terrain) {
  return p.y - terrain_height(glm::dvec2(p.x, p.z), terrain);
}

}  // namespace clmarch

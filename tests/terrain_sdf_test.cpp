// The terrain primitive: the lattice hash and noises of the reference against their closed forms
// (lattice values, analytic gradients, continuity), terrain heights against hand-summed octaves,
// the generated OpenCL map() against the reference (the same hash bit for bit, the same heights
// to float rounding) at packet widths 1 and 16, the scene keys, and noise.cl being compiled in
// only for scenes with a terrain.
#include "codegen/kernel_source.hpp"
#include "common/errors.hpp"
#include "reference/reference_noise.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"
#include "support/tolerances.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace clmarch {
namespace {

using testing::error_of;
using testing::kExact;
using testing::scene_from_yaml;

std::vector<glm::dvec2> random_points_2d(std::size_t count, double extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-extent, extent);
  std::vector<glm::dvec2> points;
  for (std::size_t i = 0; i < count; ++i) points.push_back({coord(rng), coord(rng)});
  return points;
}

TEST(NoiseHash, LatticeValuesAreUniformAndIndependent) {
  // 24-bit values: exactly k / 2^24. Over a block of the lattice their mean is 1/2 and their
  // variance 1/12, and neither neighbours nor seeds correlate (a weak hash shows stripes here).
  double sum = 0.0, square = 0.0, neighbour = 0.0, across_seeds = 0.0;
  int count = 0;
  for (int i = -150; i < 150; ++i) {
    for (int j = -150; j < 150; ++j) {
      const auto ix = static_cast<std::uint32_t>(i), iz = static_cast<std::uint32_t>(j);
      const double v = noise_hash01(ix, iz, 0) - 0.5;
      EXPECT_EQ(std::ldexp(noise_hash01(ix, iz, 0), 24), std::floor(std::ldexp(noise_hash01(ix, iz, 0), 24)));
      sum += v;
      square += v * v;
      neighbour += v * (noise_hash01(ix + 1u, iz, 0) - 0.5) + v * (noise_hash01(ix, iz + 1u, 0) - 0.5);
      across_seeds += v * (noise_hash01(ix, iz, 1) - 0.5);
      ++count;
    }
  }
  EXPECT_NEAR(sum / count, 0.0, 0.005);
  EXPECT_NEAR(square / count, 1.0 / 12.0, 0.002);
  EXPECT_NEAR(neighbour / (2 * count) * 12.0, 0.0, 0.02);
  EXPECT_NEAR(across_seeds / count * 12.0, 0.0, 0.02);
}

TEST(NoiseHash, LatticeCellsSaturateLikeOpenCl) {
  EXPECT_EQ(noise_lattice(2.5), 2);
  EXPECT_EQ(noise_lattice(-2.5), -3);
  EXPECT_EQ(noise_lattice(-3.0), -3);
  EXPECT_EQ(noise_lattice(1e12), 2147483647);
  EXPECT_EQ(noise_lattice(-1e12), -2147483647 - 1);
  EXPECT_EQ(noise_lattice(std::nan("")), 0);
}

TEST(ValueNoise, EqualsTheHashOnTheLatticeWithZeroGradient) {
  for (std::uint32_t seed : {0u, 7u}) {
    for (int i = -5; i <= 5; ++i) {
      for (int j = -5; j <= 5; ++j) {
        const NoiseSample n = value_noise({i, j}, seed);
        EXPECT_EQ(n.value, noise_hash01(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), seed));
        EXPECT_EQ(n.gradient, glm::dvec2(0.0));
        EXPECT_EQ(perlin_noise({i, j}, seed), 0.0);
      }
    }
  }
}

TEST(ValueNoise, GradientIsTheDerivativeOfTheValue) {
  // Central differences of step h agree with the analytic gradient to O(h^2 f''') (f''' <= 12 for
  // the cubic blend) plus rounding 1e-16 / h.
  constexpr double h = 1e-5;
  constexpr double kDifferenceTolerance = 1e-8;
  for (const glm::dvec2& q : random_points_2d(500, 20.0, 3)) {
    const NoiseSample n = value_noise(q, 11);
    const double dx =
        (value_noise(q + glm::dvec2(h, 0.0), 11).value - value_noise(q - glm::dvec2(h, 0.0), 11).value) / (2 * h);
    const double dz =
        (value_noise(q + glm::dvec2(0.0, h), 11).value - value_noise(q - glm::dvec2(0.0, h), 11).value) / (2 * h);
    EXPECT_NEAR(n.gradient.x, dx, kDifferenceTolerance);
    EXPECT_NEAR(n.gradient.y, dz, kDifferenceTolerance);
    // Each partial derivative is the cubic's slope (at most 1.5) times a blend of lattice steps
    // within [-1, 1].
    EXPECT_LE(std::abs(n.gradient.x), 1.5);
    EXPECT_LE(std::abs(n.gradient.y), 1.5);
    EXPECT_GE(n.value, 0.0);
    EXPECT_LT(n.value, 1.0);
  }
}

TEST(ValueNoise, BothNoisesAreContinuousAcrossCellWalls) {
  for (int k = -3; k <= 3; ++k) {
    for (double z : {0.25, 0.5, 3.75}) {
      const glm::dvec2 below(k - 1e-10, z), above(k + 1e-10, z);
      EXPECT_NEAR(value_noise(below, 1).value, value_noise(above, 1).value, 1e-9);
      EXPECT_NEAR(value_noise(below, 1).gradient.y, value_noise(above, 1).gradient.y, 1e-9);
      EXPECT_NEAR(perlin_noise(below, 1), perlin_noise(above, 1), 1e-9);
      EXPECT_NEAR(perlin_noise({z, k - 1e-10}, 1), perlin_noise({z, k + 1e-10}, 1), 1e-9);
    }
  }
}

TEST(TerrainHeight, HandSummedOctaves) {
  // At the origin every octave samples q = 0 (rotating and scaling 0 leaves it there), where the
  // value noise is the lattice value v and its gradient is 0.
  const double v = noise_hash01(0u, 0u, 5);
  Terrain t;
  t.height = -1.0;
  t.amplitude = 2.0;
  t.seed = 5;
  t.octaves = 3;
  EXPECT_NEAR(terrain_height({0.0, 0.0}, t), -1.0 + 2.0 * v * (1.0 + 0.5 + 0.25), kExact);
  t.noise = TerrainNoise::Derivative;
  // Weights 2.5, -1, 0.4; the sum is damped by 0.85 after each octave.
  EXPECT_NEAR(terrain_height({0.0, 0.0}, t), -1.0 + 2.0 * (((2.5 * v * 0.85) - v) * 0.85 + 0.4 * v) * 0.85, kExact);
  t.noise = TerrainNoise::Perlin;
  EXPECT_NEAR(terrain_height({0.0, 0.0}, t), -1.0, kExact);
  // Off the lattice, one octave of value noise is the noise at frequency * (x, z).
  t.noise = TerrainNoise::Value;
  t.octaves = 1;
  t.frequency = 0.3;
  EXPECT_NEAR(terrain_height({2.0, -7.0}, t), -1.0 + 2.0 * value_noise({0.6, -2.1}, 5).value, kExact);
  // The second octave is turned by (0.8, 0.6; -0.6, 0.8) and doubled: (0.6, -2.1) -> (-1.56, -4.08).
  t.octaves = 2;
  EXPECT_NEAR(terrain_height({2.0, -7.0}, t),
              -1.0 + 2.0 * (value_noise({0.6, -2.1}, 5).value + 0.5 * value_noise({-1.56, -4.08}, 5).value), kExact);
  // Without amplitude the ground is flat, and the distance is exact.
  t.amplitude = 0.0;
  EXPECT_EQ(sd_terrain({123.0, 4.5, -77.0}, t), 5.5);
}

TEST(TerrainHeight, StepFactorFromTheSlopeBoundMakesItOneLipschitz) {
  // docs/scene-format.md's provable factor for value noise: 1 / (1 + A F octaves 1.5 sqrt(2)).
  Terrain t;
  t.amplitude = 1.5;
  t.frequency = 0.7;
  t.octaves = 9;
  Node node;
  node.kind = NodeKind::Terrain;
  node.params = t;
  node.step_factor = 1.0 / (1.0 + t.amplitude * t.frequency * t.octaves * 1.5 * std::sqrt(2.0));
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> coord(-10.0, 10.0), offset(-0.2, 0.2);
  double steepest_unscaled = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 p(coord(rng), coord(rng), coord(rng));
    const glm::dvec3 q = p + glm::dvec3(offset(rng), offset(rng), offset(rng));
    const double change = std::abs(reference_distance(node, q) - reference_distance(node, p));
    EXPECT_LE(change, glm::length(q - p) + 1e-12);
    steepest_unscaled = std::max(steepest_unscaled, change / node.step_factor / glm::length(q - p));
  }
  EXPECT_GT(steepest_unscaled, 1.5) << "the unscaled height field is steeper than 1, or this test shows nothing";
}

// Kernel against reference at points of the sampled box, with every noise.
void expect_terrain_kernel_matches_reference(const std::string& sdf_yaml, double tolerance) {
  const Scene scene = scene_from_yaml("sdf:\n  " + sdf_yaml + "\n");
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> coord(-20.0, 20.0);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 2048; ++i) points.push_back({coord(rng), coord(rng), coord(rng)});
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    const PointSamples samples = eval_points_opencl(scene, points, options);
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_NEAR(samples.distance[i], reference_distance(scene.sdf, points[i]), tolerance)
          << sdf_yaml << " lanes " << lanes << " at " << points[i].x << " " << points[i].y << " " << points[i].z;
      EXPECT_EQ(samples.distance[i], samples.color_distance[i]) << "map and map_color disagree";
    }
  }
}

TEST(TerrainKernel, MatchesTheReference) {
  // Float rounds octave i's sample point by about (i + 2) u |q_i| (u = 2^-24; the product by the
  // frequency and i turns), and the noise turns that into height at its slope times the octave's
  // weight: ~2 (i + 2) u F |p| A per octave for value noise (weight 0.5^i at frequency 2^i), about
  // 6e-4 over 16 octaves at |p| <= 35 as a first-order worst case; measured 5e-5. A different hash,
  // weight or turn moves heights by 1e-2 and more.
  constexpr double kTerrainTolerance = 1e-3;
  expect_terrain_kernel_matches_reference("terrain: {octaves: 16}", kTerrainTolerance);
  expect_terrain_kernel_matches_reference("terrain: {noise: perlin, octaves: 16, seed: 99}", kTerrainTolerance);
  expect_terrain_kernel_matches_reference("terrain: {noise: derivative, octaves: 16, seed: 2147483647}",
                                          kTerrainTolerance);
  expect_terrain_kernel_matches_reference(
      "terrain: {height: -2, amplitude: 3, frequency: 0.06, octaves: 8, noise: derivative, step_factor: 0.5}",
      kTerrainTolerance);
}

TEST(TerrainKernel, LatticeValuesAreTheReferenceHashBitForBit) {
  // One octave at frequency 1 on integer (x, z): the height is the lattice value k / 2^24, exact
  // in float, so the kernel's distance -v must equal the reference's exactly: the kernel's uint
  // arithmetic wraps like the reference's, for negative and large cells and every seed.
  const std::vector<glm::dvec3> lattice = {{0, 0, 0},
                                           {1, 0, 0},
                                           {0, 0, 1},
                                           {-1, 0, -1},
                                           {12345, 0, -6789},
                                           {-2000000, 0, 3000000},
                                           {16000000, 0, -16000000}};
  for (std::uint32_t seed : {0u, 1u, 2147483647u}) {
    const Scene scene = scene_from_yaml(fmt::format("sdf: {{terrain: {{octaves: 1, seed: {}}}}}\n", seed));
    for (int lanes : {1, 16}) {
      OpenClOptions options;
      options.lanes = lanes;
      const PointSamples samples = eval_points_opencl(scene, lattice, options);
      for (std::size_t i = 0; i < lattice.size(); ++i) {
        const auto ix = static_cast<std::uint32_t>(static_cast<std::int32_t>(lattice[i].x));
        const auto iz = static_cast<std::uint32_t>(static_cast<std::int32_t>(lattice[i].z));
        EXPECT_EQ(samples.distance[i], static_cast<float>(-noise_hash01(ix, iz, seed)))
            << "seed " << seed << " lanes " << lanes << " at " << lattice[i].x << ", " << lattice[i].z;
      }
    }
  }
}

TEST(TerrainKeys, DefaultsAndRanges) {
  const Terrain t = std::get<Terrain>(scene_from_yaml("sdf: {terrain: {}}\n").sdf.params);
  EXPECT_EQ(t.height, 0.0);
  EXPECT_EQ(t.amplitude, 1.0);
  EXPECT_EQ(t.frequency, 1.0);
  EXPECT_EQ(t.octaves, 6);
  EXPECT_EQ(t.noise, TerrainNoise::Value);
  EXPECT_EQ(t.seed, 0u);
  const Terrain d = std::get<Terrain>(scene_from_yaml("sdf: {terrain: {noise: derivative, seed: 42}}\n").sdf.params);
  EXPECT_EQ(d.noise, TerrainNoise::Derivative);
  EXPECT_EQ(d.seed, 42u);

  EXPECT_EQ(error_of("sdf: {terrain: {noise: simplex}}\n"),
            "s.yaml:1:24: sdf.terrain.noise must be one of value, perlin, derivative (got 'simplex')");
  EXPECT_EQ(error_of("sdf: {terrain: {octaves: 17}}\n"),
            "s.yaml:1:26: sdf.terrain.octaves must be in [1, 16] (got 17)");
  EXPECT_EQ(error_of("sdf: {terrain: {seed: -1}}\n"),
            "s.yaml:1:23: sdf.terrain.seed must be in [0, 2147483647] (got -1)");
  EXPECT_EQ(error_of("sdf: {terrain: {frequency: 0}}\n"), "s.yaml:1:28: sdf.terrain.frequency must be > 0 (got 0)");
  EXPECT_EQ(error_of("sdf: {terrain: {amplitude: -1}}\n"), "s.yaml:1:28: sdf.terrain.amplitude must be >= 0 (got -1)");
  EXPECT_NE(error_of("sdf: {terrain: {center: [0, 0, 0]}}\n").find("unknown key 'center' in sdf.terrain"),
            std::string::npos);
}

TEST(TerrainKernelSource, NoiseIsCompiledInOnlyWhenUsed) {
  const auto source_of = [](const std::string& sdf) {
    return generate_kernel_source(scene_from_yaml("sdf:\n  " + sdf + "\n"), {KernelPurpose::DepthSteps, 1});
  };
  const std::string marker = "#line 1 \"kernels/noise.cl\"";
  EXPECT_EQ(source_of("menger: {}").find(marker), std::string::npos);
  const std::string terrain = source_of("union: [{sphere: {}}, {terrain: {noise: perlin, octaves: 3, seed: 9}}]");
  EXPECT_NE(terrain.find(marker), std::string::npos);
  EXPECT_NE(terrain.find("sd_terrain_perlin(p, 0.0f, 1.0f, 1.0f, 3, 9u)"), std::string::npos);
  EXPECT_EQ(terrain.find("kernels/fractals.cl"), std::string::npos);
}

}  // namespace
}  // namespace clmarch

// Non-exact distance fields (issue 7): with a step factor that makes the field a bound, the OpenCL
// march never tunnels through a surface the double reference sees at that factor; with factor 1
// a steep terrain and a low-power Mandelbulb overstep and the count below shows it. Exact-enough
// bounds (displacement, smooth operators, the Menger sponge) need no factor. CLMARCH_STRESS_SWEEP=1
// prints the table of docs/accuracy.md.
#include "reference/reference_renderer.hpp"
#include "stress_support.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <iostream>

namespace clmarch {
namespace {

using namespace stress;

constexpr int kStepImageWidth = 64;
constexpr int kStepImageHeight = 36;
constexpr int kMaxSteps = 3000;
// A ray tunnels when it ends this much deeper than the reference's hit, or misses where the
// reference hits (tiling.md's and scene-format.md's criterion): four times the depth tolerance of
// a bound, epsilon / (factor cos) <= 1e-4 / (0.08 * 0.1) = 0.0125, so only a step past the surface
// counts (through it, or into the solid behind it).
constexpr double kTunnelDepth = 0.05;

/// A scene whose field needs a step factor, with {factor} left to fill in.
struct StepFactorCase {
  const char* name;
  std::string yaml;  // the sdf line, containing step_factor: {0}
  const char* camera;
  /// A factor that provably (terrain) or by measurement (Mandelbulb) makes the field a bound.
  double safe_factor;
  /// Whether factor 1 is known to overstep (the test then insists it shows).
  bool oversteps_at_one;
};

// Terrain (value noise): slope bound L = amplitude * frequency * octaves * 1.5 * sqrt(2) =
// 1.5 * 1.2 * 3 * 2.12 = 11.5 (docs/scene-format.md), factor 1 / (1 + L) = 0.08.
const StepFactorCase kCases[] = {
    {"terrain", "terrain: {{amplitude: 1.5, frequency: 1.2, octaves: 3, step_factor: {0}}}",
     "{position: [0, 3.5, 6], look_at: [0, 0, 0]}", 0.08, true},
    {"mandelbulb_power2", "mandelbulb: {{power: 2, step_factor: {0}}}",
     "{position: [0.3, 0.4, 2.6], look_at: [0, 0, 0]}", 0.25, true},
    {"displace", "displace: {{amplitude: 0.15, frequency: 9, step_factor: {0}, children: [{{sphere: {{radius: 1}}}}]}}",
     "{position: [0, 1, 3], look_at: [0, 0, 0]}", 1.0, false},
    {"smooth_blend",
     "smooth_union: {{k: 0.6, step_factor: {0}, children: [{{sphere: {{radius: 0.7}}}}, {{box: {{center: [0.9, 0, "
     "0]}}}}, {{torus: {{center: [-0.6, 0.2, 0], major_radius: 0.6, minor_radius: 0.15}}}}]}}",
     "{position: [0.5, 1.5, 3], look_at: [0, 0, 0]}", 1.0, false},
    {"menger", "menger: {{half_size: 1, iterations: 3, step_factor: {0}}}",
     "{position: [1.6, 1.3, 2.2], look_at: [0, 0, 0]}", 1.0, false},
};

Scene bound_scene(const StepFactorCase& c, double factor) {
  return testing::scene_from_yaml(
      fmt::format("camera: {}\nrender: {{width: {}, height: {}, max_steps: {}, max_distance: 20}}\nsdf: {{{}}}\n",
                  c.camera, kStepImageWidth, kStepImageHeight, kMaxSteps, fmt::format(fmt::runtime(c.yaml), factor)));
}

struct Tunnelling {
  int reference_hits = 0;
  /// Pixels that end more than kTunnelDepth deeper than the reference, or miss where it hits.
  int tunnelled = 0;
  /// Pixels that miss by running out of steps.
  int budget_misses = 0;
  double mean_steps = 0.0;
};

Tunnelling compare(const FrameBuffers& opencl, const FrameBuffers& reference) {
  Tunnelling t;
  for (int j = 0; j < kStepImageHeight; ++j) {
    for (int i = 0; i < kStepImageWidth; ++i) {
      const float truth = reference.at(Channel::Depth, i, j), depth = opencl.at(Channel::Depth, i, j);
      t.mean_steps += opencl.at(Channel::Steps, i, j) / (kStepImageWidth * kStepImageHeight);
      if (!std::isfinite(depth) && opencl.at(Channel::Steps, i, j) == kMaxSteps) ++t.budget_misses;
      if (!std::isfinite(truth)) continue;
      ++t.reference_hits;
      if (!std::isfinite(depth) || depth > truth + kTunnelDepth) ++t.tunnelled;
    }
  }
  return t;
}

TEST(NonExactFields, TheStepFactorPreventsTunnelling) {
  for (const StepFactorCase& c : kCases) {
    SCOPED_TRACE(c.name);
    const FrameBuffers reference = render_reference(bound_scene(c, c.safe_factor));
    const Tunnelling safe = compare(render_checked(bound_scene(c, c.safe_factor), KernelPurpose::Normals), reference);
    EXPECT_GT(safe.reference_hits, kStepImageWidth * kStepImageHeight / 10);
    EXPECT_EQ(safe.tunnelled, 0);
    EXPECT_EQ(safe.budget_misses, 0);
    if (c.oversteps_at_one) {
      const Tunnelling plain = compare(render_checked(bound_scene(c, 1.0), KernelPurpose::Normals), reference);
      EXPECT_GT(plain.tunnelled, 0) << "factor 1 no longer oversteps: pick a steeper case";
    }
  }
}

// The table of docs/accuracy.md: tunnelled pixels and mean steps per factor.
TEST(NonExactFields, Sweep) {
  if (!sweep_requested()) GTEST_SKIP() << "set CLMARCH_STRESS_SWEEP=1 to measure every factor";
  std::cout << "| field | reference factor | factor | tunnelled px | budget misses | mean steps |\n";
  for (const StepFactorCase& c : kCases) {
    const FrameBuffers reference = render_reference(bound_scene(c, c.safe_factor));
    for (double factor : {1.0, 0.75, 0.5, c.safe_factor}) {
      if (factor == c.safe_factor && factor == 1.0) continue;  // already measured first
      const Tunnelling t = compare(render_checked(bound_scene(c, factor), KernelPurpose::Normals), reference);
      std::cout << fmt::format("| {} | {} | {} | {} of {} | {} | {:.1f} |\n", c.name, c.safe_factor, factor,
                               t.tunnelled, t.reference_hits, t.budget_misses, t.mean_steps);
    }
  }
}

}  // namespace
}  // namespace clmarch

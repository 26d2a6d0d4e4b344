// March settings pushed to their edges (issue 7): the same scene at scales 1e-4 and 1e4, the step
// budget running out (the documented miss rule), and degenerate values: fov near 0 and 180, one
// pixel wide or high, epsilon below float's resolution, max_distance at float's maximum, max_steps
// 1 and 10^6. Each gives a one-line input error or a finite result by a documented rule,
// repeatably.
#include "analytic_intersections.hpp"
#include "check/cross_check.hpp"
#include "common/errors.hpp"
#include "reference/reference_renderer.hpp"
#include "stress_support.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>

namespace clmarch {
namespace {

using namespace stress;

// Every length of the scene times s: camera, primitives, blend radius, epsilon, normal step and
// max_distance. Directional light and colors have no length.
std::string scaled_scene(double s) {
  return fmt::format(
      "camera: {{position: [{0}, {1}, {2}], look_at: [0, {3}, 0], fov: 45}}\n"
      "render: {{width: 64, height: 36, epsilon: {4}, normal_epsilon: {5}, max_distance: {6}, max_steps: 400}}\n"
      "sdf:\n"
      "  union:\n"
      "    - plane: {{normal: [0, 1, 0], offset: 0}}\n"
      "    - smooth_union: {{k: {7}, children: [{{sphere: {{center: [0, {8}, 0], radius: {8}}}}},"
      " {{capsule: {{a: [0, {8}, 0], b: [{8}, {9}, 0], radius: {10}}}}}]}}\n"
      "    - box: {{center: [{9}, {11}, {12}], half_size: [{11}, {11}, {11}]}}\n"
      "    - torus: {{center: [{13}, {10}, {8}], major_radius: {8}, minor_radius: {10}}}\n"
      "lights: [{{directional: {{direction: [1, 2, 1.5]}}}}]\n"
      "shading: {{model: blinn_phong, specular: 0.3}}\n",
      3.0 * s, 2.0 * s, 4.0 * s, 0.3 * s, 1e-4 * s, 1e-3 * s, 20.0 * s, 0.2 * s, 0.5 * s, 1.2 * s, 0.15 * s, 0.3 * s,
      -0.8 * s, -1.2 * s);
}

/// buffers of the scene at scale s with depth divided by s, to compare with the scene at scale 1.
FrameBuffers unscaled(FrameBuffers buffers, double s) {
  for (float& depth : buffers.plane(Channel::Depth)) depth = static_cast<float>(depth / s);
  return buffers;
}

// Scaling every length by s scales every depth by s and leaves normals, steps and colors alone;
// float keeps its relative precision from 1e-38 to 1e38, so the scaled renders pass the
// cross-check's tolerances (docs/accuracy.md) against the unit render once depths are divided by s.
TEST(Scale, SameImageAt1eMinus4And1e4) {
  const Scene unit = testing::scene_from_yaml(scaled_scene(1.0));
  const FrameBuffers base = render_checked(unit, KernelPurpose::Shaded);
  for (double s : {1e-4, 1e4}) {
    SCOPED_TRACE(fmt::format("scale {}", s));
    const FrameBuffers scaled = unscaled(render_checked(testing::scene_from_yaml(scaled_scene(s))), s);
    const CheckReport report = cross_check(unit, scaled, base);
    EXPECT_TRUE(report.passed()) << report.to_text();
    EXPECT_EQ(report.mask_mismatch_interior, 0) << report.to_text();
    EXPECT_GT(report.both_hit, 64 * 36 / 2);
  }
}

// At scales that are powers of two every float operation of the march scales exactly (no
// constant of the distance code has a length), so depths scale bit for bit and the rest is equal.
// Upwards only while the camera stays within 32 of the origin on each axis: beyond, the map frame
// origin (a 64-unit grid, host/scene/camera_model.hpp) moves and the coordinates the device sees
// no longer scale exactly; SameImageAt1eMinus4And1e4 covers 1e4 within tolerance.
TEST(Scale, PowersOfTwoScaleBitForBit) {
  const FrameBuffers base = render(testing::scene_from_yaml(scaled_scene(1.0)), KernelPurpose::Normals);
  for (double s : {0x1p-13, 0x1p2}) {
    SCOPED_TRACE(fmt::format("scale {}", s));
    const FrameBuffers scaled = unscaled(render(testing::scene_from_yaml(scaled_scene(s)), KernelPurpose::Normals), s);
    EXPECT_TRUE(bitwise_equal(base, scaled));
  }
}

// Camera straight above an endless floor, looking down; the centre pixel of a 3x3 image runs
// exactly along -y. Its first step goes 2 (the height), its second finds distance 0: a hit on the
// second step. With a budget of 1 the same ray is a miss by the budget rule.
std::string head_on_floor(int max_steps) {
  return fmt::format(
      "camera: {{position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}}\n"
      "render: {{width: 3, height: 3, max_steps: {}, over_relaxation: 1}}\n"
      "sdf: {{plane: {{}}}}\n"
      "lights: [{{directional: {{direction: [0, 1, 0]}}}}]\n"
      "shading: {{background: [0.25, 0.5, 0.75]}}\n",
      max_steps);
}

TEST(StepBudget, AHitOnTheLastStepCountsAndOneStepShortIsAMiss) {
  for (bool reference : {false, true}) {
    SCOPED_TRACE(reference ? "reference" : "opencl");
    const auto render_either = [&](const Scene& scene) {
      return reference ? render_reference(scene) : render_checked(scene, KernelPurpose::Shaded);
    };
    const Scene two = testing::scene_from_yaml(head_on_floor(2));
    const FrameBuffers hit = render_either(two);
    EXPECT_EQ(hit.at(Channel::Depth, 1, 1), 2.0f);
    EXPECT_EQ(hit.at(Channel::Steps, 1, 1), 2.0f);
    EXPECT_EQ(hit.at(Channel::NY, 1, 1), 1.0f);

    const Scene one = testing::scene_from_yaml(head_on_floor(1));
    const FrameBuffers miss = render_either(one);
    EXPECT_EQ(invariant_violation(miss, 1, true), "");
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        // Out of steps: depth +inf, steps = the budget, normal 0, the background's color.
        EXPECT_EQ(miss.at(Channel::Depth, i, j), INFINITY);
        EXPECT_EQ(miss.at(Channel::Steps, i, j), 1.0f);
        EXPECT_EQ(miss.at(Channel::NX, i, j), 0.0f);
        EXPECT_EQ(miss.at(Channel::NY, i, j), 0.0f);
        EXPECT_EQ(miss.at(Channel::NZ, i, j), 0.0f);
        EXPECT_FLOAT_EQ(miss.at(Channel::R, i, j), 0.25f);
        EXPECT_FLOAT_EQ(miss.at(Channel::G, i, j), 0.5f);
        EXPECT_FLOAT_EQ(miss.at(Channel::B, i, j), 0.75f);
      }
    }
  }
}

// Budgets from 1 to 64 on the torus: every pixel either hits within the budget or ends as a miss
// at steps == max_steps or beyond max_distance, and kernel and reference take the same decision
// except where the last step lands within rounding of the threshold.
TEST(StepBudget, EveryBudgetEndsEveryPixelByTheRule) {
  for (int budget : {1, 2, 5, 16, 64}) {
    SCOPED_TRACE(fmt::format("max_steps {}", budget));
    const Scene scene =
        testing::scene_from_yaml(fmt::format("camera: {{position: [0, 2.5, 3], look_at: [0, 0, 0]}}\n"
                                             "render: {{width: 48, height: 27, max_steps: {}, max_distance: 20}}\n"
                                             "sdf: {{torus: {{major_radius: 1, minor_radius: 0.3}}}}\n",
                                             budget));
    const FrameBuffers opencl = render_checked(scene, KernelPurpose::Normals);
    const FrameBuffers reference = render_reference(scene);
    EXPECT_EQ(invariant_violation(reference, budget, false), "") << "reference";
    int differing = 0, hits = 0, marched = 0;
    for (int j = 0; j < 27; ++j) {
      for (int i = 0; i < 48; ++i) marched += opencl.at(Channel::Steps, i, j) > 0.0f;
    }
    for (int j = 0; j < 27; ++j) {
      for (int i = 0; i < 48; ++i) {
        const bool hit = std::isfinite(opencl.at(Channel::Depth, i, j));
        hits += hit;
        if (hit != std::isfinite(reference.at(Channel::Depth, i, j))) ++differing;
      }
    }
    // The rays out of steps, counted on both sides: with one step every ray that marched is out of
    // steps unless that step left the scene's bounding sphere (the first step from 3.9 away cannot
    // reach max_distance 20), and both sides decide alike.
    const std::uint64_t out_opencl = opencl.rays_with_status(RayStatus::OutOfSteps);
    const std::uint64_t out_reference = reference.rays_with_status(RayStatus::OutOfSteps);
    EXPECT_LE(std::max(out_opencl, out_reference) - std::min(out_opencl, out_reference),
              static_cast<std::uint64_t>(48 * 27 / 50));
    if (budget == 1) {
      EXPECT_EQ(hits, 0) << "one step from outside cannot arrive";
      EXPECT_EQ(out_opencl, out_reference);
      EXPECT_GT(out_opencl, static_cast<std::uint64_t>(marched / 2));
      EXPECT_EQ(opencl.rays_with_status(RayStatus::OutOfDistance), 0u);
      EXPECT_EQ(opencl.rays_with_status(RayStatus::OutOfSteps) + opencl.rays_with_status(RayStatus::Miss),
                static_cast<std::uint64_t>(48 * 27));
    }
    if (budget == 64) {
      EXPECT_LT(out_opencl, static_cast<std::uint64_t>(marched - hits));
    }
    if (budget == 64) {
      EXPECT_GT(hits, 48 * 27 / 10);
    }
    // Rounding near the threshold can move a ray's last step: a few per cent of pixels at most.
    EXPECT_LE(differing, 48 * 27 / 50);
  }
}

// A floor seen at grazing angles 2e4 away: near the hit, steps d shrink geometrically while t is
// ~2e4, whose float spacing (0.002) is 20 times epsilon. Before the threshold had its floor of
// 2^-23 t, d fell below half that spacing, t + d == t, and every ray of this image stalled until
// its budget ran out (576 of 576 budget misses with the fixed threshold, none in the reference).
// Now each arrives, within threshold / cos of the floor, the threshold being
// max(epsilon, cone, 2^-23 t) (docs/scene-format.md).
TEST(StepBudget, FarGrazingRaysArriveInsteadOfStalling) {
  const Plane floor{{0, 1, 0}, 0.0};
  for (const char* threshold : {"fixed", "pixel_cone"}) {
    SCOPED_TRACE(threshold);
    const Scene scene = testing::scene_from_yaml(
        fmt::format("camera: {{position: [0, 1000, 0], look_at: [0, 0, -20000], fov: 1}}\n"
                    "render: {{width: 32, height: 18, max_steps: 500, max_distance: 100000, hit_threshold: {}}}\n"
                    "sdf: {{plane: {{}}}}\n",
                    threshold));
    const FrameBuffers b = render_checked(scene, KernelPurpose::DepthSteps);
    const double slope = hit_cone_slope(scene.render, scene.camera);
    for (int j = 0; j < b.height; ++j) {
      for (int i = 0; i < b.width; ++i) {
        const glm::dvec3 d = ray_direction(scene, i, j);
        const double t_exact = *intersect_plane(scene.camera.position, d, floor);
        const float depth = b.at(Channel::Depth, i, j);
        ASSERT_TRUE(std::isfinite(depth))
            << i << "," << j << ": a miss after " << b.at(Channel::Steps, i, j) << " steps";
        // threshold / cos in front of the floor at most; float rounding of t (16u t) either side.
        const double threshold_there = std::max({scene.render.epsilon, slope * t_exact, 0x1p-23 * t_exact});
        const double rounding = kFloatRelative * (glm::length(scene.camera.position) + t_exact);
        EXPECT_LE(t_exact - depth, threshold_there / std::abs(d.y) + rounding) << i << "," << j;
        EXPECT_GE(t_exact - depth, -rounding) << i << "," << j;
      }
    }
  }
}

// The largest budget (10^6) ends: rays exactly parallel to a floor 1.5 epsilon below them step
// 1.5e-4 at a time and run through their whole budget (the reference too), nothing hangs.
TEST(StepBudget, TheLargestBudgetEnds) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 1.5e-4, 0], look_at: [0, 1.5e-4, -1]}\n"
      "render: {width: 9, height: 1, max_steps: 1000000, max_distance: 10000}\n"
      "sdf: {plane: {}}\n");
  const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
  const FrameBuffers reference = render_reference(scene);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(opencl.at(Channel::Depth, i, 0), INFINITY) << i;
    EXPECT_EQ(opencl.at(Channel::Steps, i, 0), 1e6f) << i;
    EXPECT_EQ(reference.at(Channel::Steps, i, 0), 1e6f) << i;
  }
}

/// A unit sphere and a floor seen from a given camera.
Scene degenerate_scene(const std::string& camera, const std::string& render) {
  return testing::scene_from_yaml(
      fmt::format("camera: {}\nrender: {}\n"
                  "sdf: {{union: [{{sphere: {{radius: 1}}}}, {{plane: {{normal: [0, 1, 0], offset: 1}}}}]}}\n"
                  "lights: [{{directional: {{direction: [1, 2, 3]}}}}]\n",
                  camera, render));
}

// Extreme but valid settings give finite images that the reference confirms within the
// cross-check's tolerances.
TEST(DegenerateSettings, ExtremeValidValuesCrossCheck) {
  const struct {
    const char* camera;
    const char* render;
  } cases[] = {
      {"{position: [0, 0, 5], fov: 1.0e-6}", "{width: 16, height: 9}"},  // all rays one direction in float
      {"{position: [0, 0, 5], fov: 0.01}", "{width: 16, height: 9}"},
      {"{position: [0, 0, 5], fov: 179.9}", "{width: 32, height: 18}"},
      {"{position: [0, 0, 5], fov: 179.9999999}", "{width: 32, height: 18}"},
      {"{position: [0, 0.5, 5]}", "{width: 1, height: 1}"},
      {"{position: [0, 0.5, 5]}", "{width: 1, height: 40}"},
      {"{position: [0, 0.5, 5]}", "{width: 40, height: 1}"},
      {"{position: [0, 0.5, 5]}", "{width: 32, height: 18, max_steps: 1}"},
      {"{position: [0, 0.5, 5]}", "{width: 32, height: 18, max_distance: 1.0e+30}"},
      // The largest max_distance: sky rays step ever longer until t overflows (a miss) or the budget ends.
      {"{position: [0, 0.5, 5]}", "{width: 32, height: 18, max_distance: 3.0e+38}"},
      {"{position: [0, 0.5, 5]}", "{width: 32, height: 18, max_distance: 3.0e+38, max_steps: 100000}"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(fmt::format("camera {} render {}", c.camera, c.render));
    const Scene scene = degenerate_scene(c.camera, c.render);
    const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
    const FrameBuffers reference = render_reference(scene);
    EXPECT_EQ(invariant_violation(reference, scene.render.max_steps, true), "") << "reference";
    const CheckReport report = cross_check(scene, opencl, reference, reshade_hits(scene, opencl));
    EXPECT_TRUE(report.passed()) << report.to_text();
  }
}

// An epsilon below float's resolution (1e-12, and 1e-45 and 1e-300, which round to a denormal and
// to 0 on the device) acts as the threshold's floor 2^-23 t: rays arrive as with a usable epsilon
// instead of stalling until the budget ends (before the floor: 60 or 20 hits where epsilon 1e-4
// gives 342, nearly all others out of steps). The double reference honours such an epsilon and is
// not compared here.
TEST(DegenerateSettings, EpsilonBelowFloatResolutionActsAsTheFloor) {
  const auto tally = [](const FrameBuffers& b, int budget) {
    std::pair<int, int> hits_and_budget_misses{0, 0};
    for (std::size_t k = 0; k < b.plane(Channel::Depth).size(); ++k) {
      if (std::isfinite(b.plane(Channel::Depth)[k])) {
        ++hits_and_budget_misses.first;
      } else if (b.plane(Channel::Steps)[k] == static_cast<float>(budget)) {
        ++hits_and_budget_misses.second;
      }
    }
    return hits_and_budget_misses;
  };
  const Scene usable = degenerate_scene("{position: [0, 0.5, 5]}", "{width: 32, height: 18, epsilon: 1.0e-6}");
  const auto [usable_hits, usable_budget_misses] = tally(render(usable, KernelPurpose::DepthSteps), 255);
  for (const char* render_yaml :
       {"{width: 32, height: 18, epsilon: 1.0e-12}", "{width: 32, height: 18, epsilon: 1.0e-45}",
        "{width: 32, height: 18, epsilon: 1.0e-300}"}) {
    SCOPED_TRACE(render_yaml);
    const FrameBuffers b =
        render_checked(degenerate_scene("{position: [0, 0.5, 5]}", render_yaml), KernelPurpose::Shaded);
    const auto [hits, budget_misses] = tally(b, 255);
    // Silhouette rays within rounding of the threshold may go either way: 1 % of the image.
    EXPECT_NEAR(hits, usable_hits, 6);
    EXPECT_LE(budget_misses, usable_budget_misses + 6);
  }
}

// Values outside the documented ranges are one-line input errors with file:line:col, exit 2.
TEST(DegenerateSettings, OutOfRangeValuesAreOneLineErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"camera: {fov: 0}", "scene.yaml:2:15: camera.fov must be in (0, 180) (got 0)"},
      {"camera: {fov: 180}", "scene.yaml:2:15: camera.fov must be in (0, 180) (got 180)"},
      {"render: {epsilon: 0}", "scene.yaml:2:19: render.epsilon must be > 0 (got 0)"},
      {"render: {max_distance: 0}", "scene.yaml:2:24: render.max_distance must be > 0 (got 0)"},
      {"render: {max_steps: 0}", "scene.yaml:2:21: render.max_steps must be in [1, 1000000] (got 0)"},
      {"render: {max_steps: 1000001}", "scene.yaml:2:21: render.max_steps must be in [1, 1000000] (got 1000001)"},
      {"render: {normal_epsilon: 0}", "scene.yaml:2:26: render.normal_epsilon must be > 0 (got 0)"},
      {"render: {height: 0}", "scene.yaml:2:18: render.height must be in [1, 65536] (got 0)"},
      {"camera: {position: [1, 2, 3], look_at: [1, 2, 3]}", "scene.yaml:2:"},
      {"render: {max_distance: 1.0e+300}",
       "scene.yaml:2:24: render.max_distance must be within +-3.40282e+38, the float range"},
      {"render: {max_distance: 1.0e+400}", "scene.yaml:2:24: render.max_distance must be"},
  };
  testing::TempDir dir;
  for (const auto& [line, message] : cases) {
    SCOPED_TRACE(line);
    std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {}}\n" << line << "\n";
    const testing::CommandResult r =
        testing::run_clmarch({"render", (dir / "scene.yaml").string(), "-o", (dir / "out.png").string()});
    EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
  }
}

// Each value is within float's range, but the kernels need numbers made from them: 1 / scale, and
// a position relative to the camera's map frame. Past float's range they are one-line input errors
// (the OpenCL build saw "inff" and failed with exit 3 and the compiler's log); the reference,
// in double, renders the far scene.
TEST(DegenerateSettings, NumbersTheKernelsDeriveStayWithinFloat) {
  testing::TempDir dir;
  const auto render = [&](const std::string& scene, const std::string& backend) {
    std::ofstream(dir / "scene.yaml") << scene;
    return testing::run_clmarch({"render", (dir / "scene.yaml").string(), "--size", "16x9", "--backend", backend, "-o",
                                 (dir / "out.png").string()});
  };
  const testing::CommandResult tiny = render("sdf: {sphere: {scale: 1.0e-40}}\n", "opencl");
  EXPECT_EQ(tiny.exit_code, kExitBadInput) << tiny.err;
  EXPECT_EQ(tiny.err, (dir / "scene.yaml").string() +
                          ":1:23: sdf.sphere.scale must be in [2.93874e-39, 3.40282e+38] (got 1.0e-40)\n");

  const std::string far =
      "sdf: {sphere: {center: [3.0e+38, 0, 0]}}\ncamera: {position: [-3.0e+38, 0, 0], look_at: [0, 0, 0]}\n";
  const testing::CommandResult opencl = render(far, "opencl");
  EXPECT_EQ(opencl.exit_code, kExitBadInput) << opencl.err;
  EXPECT_EQ(std::count(opencl.err.begin(), opencl.err.end(), '\n'), 1) << opencl.err;
  EXPECT_EQ(opencl.err.rfind((dir / "scene.yaml").string() +
                                 ": the scene needs the number 6e+38 in its OpenCL program, beyond "
                                 "float's range",
                             0),
            0u)
      << "one line naming the file: " << opencl.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
  const testing::CommandResult reference = render(far, "reference");
  EXPECT_EQ(reference.exit_code, kExitOk) << reference.err;
}

}  // namespace
}  // namespace clmarch

// `clmarch bench` and its measuring blocks (host/bench/): the figures it prints are the ones it
// claims (counts and ratios, never timings: the machine is shared), and the ceiling kernel
// evaluates exactly the points it is given.
#include "bench/throughput.hpp"
#include "cl/devices.hpp"
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

namespace clmarch {
namespace {

using testing::run_clmarch;

// Ratios are recomputed from the printed figures, which JSON carries as doubles.
constexpr double kRatioTolerance = 1e-9;

TEST(Bench, MedianOfOddAndEvenCounts) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
}

TEST(Bench, PinsPoclThreadsUnlessTheEnvironmentChooses) {
  const char* before = std::getenv("POCL_AFFINITY");
  const std::string saved = before ? before : "";
  setenv("POCL_AFFINITY", "0", 1);
  pin_pocl_threads_for_timing();
  EXPECT_STREQ(std::getenv("POCL_AFFINITY"), "0");
  unsetenv("POCL_AFFINITY");
  pin_pocl_threads_for_timing();
  EXPECT_STREQ(std::getenv("POCL_AFFINITY"), "1");
  if (before) {
    setenv("POCL_AFFINITY", saved.c_str(), 1);
  } else {
    unsetenv("POCL_AFFINITY");
  }
}

TEST(Bench, LaneUseCountsIdleLanesOfEachTile) {
  // A 5 x 5 image in 4 x 4 tiles (16 lanes): four tiles, 25 pixels inside the image.
  std::vector<float> steps(25, 0.0f);
  steps[0] = 4.0f;   // tile (0, 0): one ray of 4 steps, 16 lanes x 4 iterations
  steps[4] = 2.0f;   // tile (1, 0): a 1-wide strip, 16 x 2
  steps[24] = 1.0f;  // tile (1, 1): the corner pixel, 16 x 1
  EXPECT_DOUBLE_EQ(lane_use(steps, 5, 5, 16), 7.0 / (16.0 * 7.0));
  EXPECT_DOUBLE_EQ(lane_use(steps, 5, 5, 1), 1.0);
  EXPECT_DOUBLE_EQ(lane_use(std::vector<float>(25, 3.0f), 5, 5, 4), 75.0 / (4.0 * 3.0 * 9.0));
  EXPECT_DOUBLE_EQ(lane_use(std::vector<float>(25, 0.0f), 5, 5, 16), 1.0);
}

TEST(Bench, CeilingReplaysExactlyTheMarchsPoints) {
  Scene scene = load_scene_file(testing::source_path("scenes/torus.yaml").string());
  // 37 x 11 = 407 rays: not a whole number of tiles or work-groups, so padding lanes exist.
  scene.render.width = 37;
  scene.render.height = 11;
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    options.purpose = KernelPurpose::DepthSteps;
    const RenderResult render = render_opencl(scene, options);
    CeilingKernel ceiling(scene, options, 3);
    EXPECT_EQ(ceiling.lanes(), lanes);
    EXPECT_GT(render.stats.steps, 0u);
    EXPECT_EQ(ceiling.marched_steps(), render.stats.steps) << "lanes " << lanes;
    EXPECT_EQ(ceiling.samples(), render.stats.steps);
    EXPECT_EQ(ceiling.pixel_stride(), 1u);
    EXPECT_EQ(ceiling.points(), 3 * render.stats.steps);
    for (int run = 0; run < 2; ++run) {
      EXPECT_GE(ceiling.run_ms(), 0.0);
      EXPECT_EQ(ceiling.counted_evaluations(), ceiling.points()) << "lanes " << lanes << ", run " << run;
    }
    EXPECT_EQ(testing::compiler_warnings(ceiling.program().build_log), "") << ceiling.program().build_log;

    // Past max_samples the points of every k-th pixel are kept: fewer, and whole rays.
    CeilingKernel capped(scene, options, 1, render.stats.steps / 3);
    EXPECT_GE(capped.pixel_stride(), 3u);
    EXPECT_LT(capped.samples(), render.stats.steps);
    std::uint64_t kept = 0;
    const std::vector<float>& steps = render.buffers.plane(Channel::Steps);
    for (std::size_t pixel = 0; pixel < steps.size(); pixel += capped.pixel_stride())
      kept += static_cast<std::uint64_t>(steps[pixel]);
    EXPECT_EQ(capped.samples(), kept);
    capped.run_ms();
    EXPECT_EQ(capped.counted_evaluations(), capped.points());
    // k is the smallest stride whose share of the steps fits: 2.5 rounds up to 3, not down to 2.
    const std::uint64_t most = render.stats.steps * 2 / 5;
    const CeilingKernel shared(scene, options, 1, most);
    const double share = static_cast<double>(render.stats.steps) / static_cast<double>(shared.pixel_stride());
    EXPECT_LE(share, static_cast<double>(most)) << "stride " << shared.pixel_stride();
    EXPECT_GT(static_cast<double>(render.stats.steps) / static_cast<double>(shared.pixel_stride() - 1),
              static_cast<double>(most));
  }
}

TEST(Bench, RecordedPointsAreTheMarchsSamples) {
  // A plane z = 0 seen from z = 5: the march starts at the camera (no cone pass) and steps by the
  // plane's exact distance (plain sphere tracing), so each pixel's k-th point is at distance z_k along its ray from the
  // previous one.
  // Float rounds z to 2^-24 relative; 1e-5 leaves room for the sums along the ray.
  constexpr double kFloatSteps = 1e-5;
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 60}\n"
      "render: {width: 9, height: 7, max_steps: 6, epsilon: 1e-6, max_distance: 100, bounds: none, coarse_pass: none, "
      "over_relaxation: 1}\n"
      "sdf: {plane: {normal: [0, 0, 1], offset: 0}}\n");
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    options.purpose = KernelPurpose::DepthSteps;
    const RenderResult render = render_opencl(scene, options);
    const std::vector<float>& steps = render.buffers.plane(Channel::Steps);
    CeilingKernel ceiling(scene, options, 1);
    const std::vector<glm::vec3> points = ceiling.read_samples();
    std::size_t at = 0;
    for (std::size_t pixel = 0; pixel < steps.size(); ++pixel) {
      ASSERT_GE(steps[pixel], 1.0f);
      for (int k = 0; k < static_cast<int>(steps[pixel]); ++k, ++at) {
        ASSERT_LT(at, points.size());
        if (k == 0) {
          EXPECT_NEAR(glm::distance(points[at], glm::vec3(0.0f, 0.0f, 5.0f)), 0.0, kFloatSteps) << "pixel " << pixel;
        } else {
          EXPECT_NEAR(glm::distance(points[at], points[at - 1]), points[at - 1].z, kFloatSteps)
              << "pixel " << pixel << " k " << k;
        }
      }
    }
    EXPECT_EQ(at, points.size()) << "lanes " << lanes;
  }
}

TEST(Bench, OutputFloorStoresEveryFloatOfEachRun) {
  OpenClOptions options;
  // 1000 floats round up to 63 whole rows of 16.
  OutputFloorKernel output_floor(options, 1000);
  EXPECT_EQ(output_floor.floats(), 1008u);
  for (float run : {1.0f, 2.0f}) {
    EXPECT_GE(output_floor.run_ms(), 0.0);
    const std::vector<float> values = output_floor.read_back();
    ASSERT_EQ(values.size(), 1008u);
    EXPECT_EQ(std::count(values.begin(), values.end(), run), 1008) << "run " << run;
  }
}

TEST(Bench, JsonHasEveryFigureAndTheyAreConsistent) {
  const testing::CommandResult r = run_clmarch(
      {"bench", testing::source_path("scenes/torus.yaml").string(), "--size", "64x36", "--repeat", "2", "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"scene",
                          "device",
                          "lanes",
                          "precision",
                          "width",
                          "height",
                          "repeat",
                          "build_ms",
                          "kernel_ms",
                          "depth_kernel_ms",
                          "rays_per_s",
                          "steps_per_pixel",
                          "evals_per_s",
                          "ceiling_evals_per_s",
                          "ceiling_kernel_ms",
                          "ceiling_points",
                          "ceiling_samples",
                          "ceiling_pixel_stride",
                          "lane_use",
                          "ceiling_ratio",
                          "depth_to_shaded_ratio",
                          "reference_ms",
                          "opencl_to_reference_ratio",
                          "output_floor_ms",
                          "output_floor_share",
                          "output_floor_planes"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing in " << r.out;
  }
  const double pixels = 64.0 * 36.0;
  EXPECT_EQ(j["width"], 64);
  EXPECT_EQ(j["repeat"], 2);
  // The ceiling replays the march's points: all of them at this size, kCeilingRepeats times each.
  EXPECT_EQ(j["ceiling_pixel_stride"], 1);
  EXPECT_EQ(j["ceiling_samples"].get<double>(), j["steps_per_pixel"].get<double>() * pixels);
  EXPECT_EQ(j["ceiling_points"], j["ceiling_samples"].get<std::uint64_t>() * kCeilingRepeats);
  EXPECT_GT(j["lane_use"].get<double>(), 0.0);
  EXPECT_LE(j["lane_use"].get<double>(), 1.0);
  const double shaded = j["kernel_ms"], depth = j["depth_kernel_ms"], reference = j["reference_ms"];
  EXPECT_GT(shaded, 0.0);
  EXPECT_GT(depth, 0.0);
  EXPECT_GT(reference, 0.0);
  const auto near = [](double a, double b) { return std::abs(a - b) <= kRatioTolerance * std::abs(b); };
  EXPECT_TRUE(near(j["rays_per_s"], pixels / (shaded * 1e-3))) << r.out;
  EXPECT_TRUE(near(j["evals_per_s"], j["steps_per_pixel"].get<double>() * pixels / (depth * 1e-3))) << r.out;
  EXPECT_TRUE(near(j["ceiling_ratio"], j["evals_per_s"].get<double>() / j["ceiling_evals_per_s"].get<double>()))
      << r.out;
  EXPECT_TRUE(near(j["depth_to_shaded_ratio"], depth / shaded)) << r.out;
  EXPECT_TRUE(near(j["opencl_to_reference_ratio"], shaded / reference)) << r.out;
  // The torus's depth-only program stores depth and steps.
  EXPECT_EQ(j["output_floor_planes"], 2);
  EXPECT_GT(j["output_floor_ms"].get<double>(), 0.0);
  EXPECT_TRUE(near(j["output_floor_share"], j["output_floor_ms"].get<double>() / depth)) << r.out;

  // Steps per pixel are the march's own count, as `render --stats` reports it.
  testing::TempDir dir;
  const testing::CommandResult stats =
      run_clmarch({"render", testing::source_path("scenes/torus.yaml").string(), "--size", "64x36", "--stats", "-q",
                   "-o", (dir / "t.png").string()});
  ASSERT_EQ(stats.exit_code, kExitOk) << stats.err;
  const double steps = nlohmann::json::parse(stats.out)["steps"];
  EXPECT_TRUE(near(j["steps_per_pixel"], steps / pixels)) << r.out;
}

// A union evaluated from its operand grid reads the grid from the values buffer: the ceiling's
// marches and replay got none and crashed the process in grid_distance.
TEST(Bench, CeilingOfAnOperandGridScene) {
  std::string yaml =
      "camera: {position: [0, 0.5, 4], look_at: [0, 0, 0]}\nrender: {width: 40, height: 24}\nsdf:\n  union:\n";
  for (int i = 0; i < 64; ++i) {
    yaml += fmt::format("    - sphere: {{center: [{}, {}, {}], radius: 0.12}}\n", (i % 4) * 0.5 - 0.75,
                        (i / 4 % 4) * 0.5 - 0.75, (i / 16) * 0.5 - 0.75);
  }
  const Scene scene = testing::scene_from_yaml(yaml);
  ASSERT_EQ(scene.render.pruning, Pruning::Auto);
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  const RenderResult render = render_opencl(scene, options);
  CeilingKernel ceiling(scene, options, 2);
  EXPECT_GT(render.stats.steps, 0u);
  EXPECT_EQ(ceiling.marched_steps(), render.stats.steps);
  EXPECT_GE(ceiling.run_ms(), 0.0);
  EXPECT_EQ(ceiling.counted_evaluations(), ceiling.points());
  testing::TempDir dir;
  std::ofstream(dir / "grid.yaml") << yaml;
  const testing::CommandResult bench =
      run_clmarch({"bench", (dir / "grid.yaml").string(), "--repeat", "1", "--json", "--no-reference"});
  ASSERT_EQ(bench.exit_code, kExitOk) << bench.err;
  EXPECT_GT(nlohmann::json::parse(bench.out)["ceiling_samples"].get<double>(), 0.0);
}

TEST(Bench, NoReferenceAndText) {
  const std::string torus = testing::source_path("scenes/torus.yaml").string();
  const testing::CommandResult json =
      run_clmarch({"bench", torus, "--size", "32x18", "--repeat", "1", "--json", "--no-reference"});
  ASSERT_EQ(json.exit_code, kExitOk) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_TRUE(j["reference_ms"].is_null());
  EXPECT_TRUE(j["opencl_to_reference_ratio"].is_null());
  const testing::CommandResult text = run_clmarch({"bench", torus, "--size", "32x18", "--repeat", "1"});
  ASSERT_EQ(text.exit_code, kExitOk) << text.err;
  for (const char* part :
       {"shaded kernel", "depth-only kernel", "per pixel", "of the ceiling", "output floor", "CPU reference"}) {
    EXPECT_NE(text.out.find(part), std::string::npos) << part << " missing in:\n" << text.out;
  }
}

TEST(Bench, BadInputIsOneLine) {
  const std::string torus = testing::source_path("scenes/torus.yaml").string();
  for (const std::vector<std::string>& args : {std::vector<std::string>{"bench", torus, "--repeat", "0"},
                                               {"bench", torus, "--set", "render.over_relaxation=2"},
                                               {"bench", torus, "--size", "0x5"},
                                               {"bench", "/no/such/scene.yaml"}}) {
    const testing::CommandResult r = run_clmarch(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace clmarch

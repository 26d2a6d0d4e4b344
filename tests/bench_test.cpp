// `clmarch bench` and its measuring blocks (host/bench/): the figures it prints are the ones it
// claims (counts and ratios, never timings: the machine is shared), and the ceiling kernel
// evaluates exactly the points it is given.
#include "bench/throughput.hpp"
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

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

TEST(Bench, CeilingKernelCountsOneEvaluationPerPoint) {
  Scene scene = load_scene_file(testing::source_path("scenes/torus.yaml").string());
  // 37 x 11 = 407 rays: not a whole number of packets or work-groups, so padding lanes exist.
  scene.render.width = 37;
  scene.render.height = 11;
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    CeilingKernel ceiling(scene, options, 5);
    EXPECT_EQ(ceiling.lanes(), lanes);
    EXPECT_EQ(ceiling.points(), 37u * 11u * 5u);
    for (int run = 0; run < 2; ++run) {
      EXPECT_GE(ceiling.run_ms(), 0.0);
      EXPECT_EQ(ceiling.counted_evaluations(), ceiling.points()) << "lanes " << lanes << ", run " << run;
    }
    EXPECT_EQ(ceiling.program().build_log.find("warning"), std::string::npos) << ceiling.program().build_log;
  }
}

TEST(Bench, JsonHasEveryFigureAndTheyAreConsistent) {
  const testing::CommandResult r =
      run_clmarch({"bench", testing::source_path("scenes/torus.yaml").string(), "--size", "64x36", "--repeat", "2", "--json"});
  ASSERT_EQ(r.exit_code, kExitOk) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"scene", "device", "lanes", "width", "height", "repeat", "build_ms", "kernel_ms", "depth_kernel_ms",
                          "rays_per_s", "steps_per_pixel", "evals_per_s", "ceiling_evals_per_s", "ceiling_kernel_ms",
                          "ceiling_points", "ceiling_ratio", "depth_to_shaded_ratio", "reference_ms",
                          "opencl_to_reference_ratio"}) {
    EXPECT_TRUE(j.contains(key)) << key << " missing in " << r.out;
  }
  const double pixels = 64.0 * 36.0;
  EXPECT_EQ(j["width"], 64);
  EXPECT_EQ(j["repeat"], 2);
  EXPECT_EQ(j["ceiling_points"], 64 * 36 * 16);
  const double shaded = j["kernel_ms"], depth = j["depth_kernel_ms"], reference = j["reference_ms"];
  EXPECT_GT(shaded, 0.0);
  EXPECT_GT(depth, 0.0);
  EXPECT_GT(reference, 0.0);
  const auto near = [](double a, double b) { return std::abs(a - b) <= kRatioTolerance * std::abs(b); };
  EXPECT_TRUE(near(j["rays_per_s"], pixels / (shaded * 1e-3))) << r.out;
  EXPECT_TRUE(near(j["evals_per_s"], j["steps_per_pixel"].get<double>() * pixels / (depth * 1e-3))) << r.out;
  EXPECT_TRUE(near(j["ceiling_ratio"], j["evals_per_s"].get<double>() / j["ceiling_evals_per_s"].get<double>())) << r.out;
  EXPECT_TRUE(near(j["depth_to_shaded_ratio"], depth / shaded)) << r.out;
  EXPECT_TRUE(near(j["opencl_to_reference_ratio"], shaded / reference)) << r.out;

  // Steps per pixel are the march's own count, as `render --stats` reports it.
  testing::TempDir dir;
  const testing::CommandResult stats = run_clmarch({"render", testing::source_path("scenes/torus.yaml").string(), "--size",
                                                    "64x36", "--stats", "-q", "-o", (dir / "t.png").string()});
  ASSERT_EQ(stats.exit_code, kExitOk) << stats.err;
  const double steps = nlohmann::json::parse(stats.out)["steps"];
  EXPECT_TRUE(near(j["steps_per_pixel"], steps / pixels)) << r.out;
}

TEST(Bench, NoReferenceAndText) {
  const std::string torus = testing::source_path("scenes/torus.yaml").string();
  const testing::CommandResult json = run_clmarch({"bench", torus, "--size", "32x18", "--repeat", "1", "--json", "--no-reference"});
  ASSERT_EQ(json.exit_code, kExitOk) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_TRUE(j["reference_ms"].is_null());
  EXPECT_TRUE(j["opencl_to_reference_ratio"].is_null());
  const testing::CommandResult text = run_clmarch({"bench", torus, "--size", "32x18", "--repeat", "1"});
  ASSERT_EQ(text.exit_code, kExitOk) << text.err;
  for (const char* part : {"shaded kernel", "depth-only kernel", "per pixel", "of the ceiling", "CPU reference"}) {
    EXPECT_NE(text.out.find(part), std::string::npos) << part << " missing in:\n" << text.out;
  }
}

TEST(Bench, BadInputIsOneLine) {
  const std::string torus = testing::source_path("scenes/torus.yaml").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"bench", torus, "--repeat", "0"}, {"bench", torus, "--set", "render.over_relaxation=2"},
        {"bench", torus, "--size", "0x5"}, {"bench", "/no/such/scene.yaml"}}) {
    const testing::CommandResult r = run_clmarch(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace clmarch

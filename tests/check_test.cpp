// The cross-check: every shipped scene passes it on the OpenCL device, and it has teeth: a
// perturbed OpenCL render fails it while the unperturbed one passes.
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace clmarch {
namespace {

using testing::source_path;

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(source_path("scenes"))) {
    if (entry.path().extension() == ".yaml" || entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

Scene small_scene(const std::string& name, const std::vector<SceneOverride>& overrides = {}) {
  Scene scene = load_scene_file(source_path("scenes/" + name).string(), overrides);
  scene.render.width = 96;
  scene.render.height = 54;
  return scene;
}

/// Renders opencl_scene on the device and scene on the reference, and compares them.
CheckReport check_against(const Scene& scene, const Scene& opencl_scene, int lanes = 16) {
  OpenClOptions options;
  options.lanes = lanes;
  const FrameBuffers opencl = render_opencl(opencl_scene, options).buffers;
  return cross_check(scene, opencl, render_reference(scene));
}

class CheckScene : public ::testing::TestWithParam<std::string> {};

TEST_P(CheckScene, PassesWithOneAndSixteenLanes) {
  const Scene scene = small_scene(GetParam());
  for (int lanes : {1, 16}) {
    const CheckReport report = check_against(scene, scene, lanes);
    EXPECT_TRUE(report.passed()) << "lanes " << lanes << "\n" << report.to_text();
    EXPECT_GT(report.both_hit, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, CheckScene, ::testing::ValuesIn(shipped_scenes()), [](const auto& info) {
  std::string name = info.param;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
});

TEST(CheckTeeth, FailsWhenEpsilonIsTenTimesLarger) {
  const Scene scene = small_scene("torus.yaml");
  const Scene perturbed = small_scene("torus.yaml", {{"render.epsilon", "1e-3"}});
  const CheckReport report = check_against(scene, perturbed);
  EXPECT_FALSE(report.passed()) << report.to_text();
  EXPECT_GT(report.depth_in_tolerances.p99, 1.0);
}

TEST(CheckTeeth, FailsWhenAPrimitiveMovesSlightly) {
  const Scene scene = small_scene("torus.yaml");
  const Scene perturbed = small_scene("torus.yaml", {{"sdf.torus.center", "[0.002, 0, 0]"}});
  const CheckReport report = check_against(scene, perturbed);
  EXPECT_FALSE(report.passed()) << report.to_text();
}

TEST(CheckTeeth, FailsWhenTheNormalMethodIsSwapped) {
  // At the default step (1e-3) both methods are exact to ~1e-6 rad, below float noise; a coarse
  // step makes their truncation errors differ visibly, and only the swap may fail the check.
  const Scene scene = small_scene("torus.yaml", {{"render.normal_epsilon", "0.05"}});
  const Scene swapped = small_scene("torus.yaml", {{"render.normal_epsilon", "0.05"}, {"render.normal_method", "tetrahedral"}});
  EXPECT_TRUE(check_against(scene, scene).passed());
  const CheckReport report = check_against(scene, swapped);
  EXPECT_FALSE(report.passed()) << report.to_text();
}

// Misses are compared too: a background 3 steps of 8 bits off, and a glow of misses 5 % weaker,
// each fail the check on the miss criterion alone.
TEST(CheckTeeth, FailsWhenTheColorOfMissesDiffers) {
  const Scene scene = small_scene("torus.yaml");
  const CheckReport background = check_against(scene, small_scene("torus.yaml", {{"shading.background", "[0.012, 0, 0]"}}));
  EXPECT_FALSE(background.passed()) << background.to_text();
  ASSERT_EQ(background.failures.size(), 1u) << background.to_text();
  EXPECT_NE(background.failures[0].find("color error of misses"), std::string::npos) << background.to_text();

  const Scene bulb = small_scene("mandelbulb.yaml");
  const CheckReport glow = check_against(bulb, small_scene("mandelbulb.yaml", {{"shading.glow.color", "[0.3325, 0.285, 0.855]"}}));
  EXPECT_FALSE(glow.passed()) << glow.to_text();
  ASSERT_EQ(glow.failures.size(), 1u) << glow.to_text();
  EXPECT_NE(glow.failures[0].find("color error of misses"), std::string::npos) << glow.to_text();
  EXPECT_GT(glow.color_compared, glow.both_hit) << "misses must be among the pixels compared";
}

TEST(CheckCli, ReportsAndExitsZeroWhenWithinTolerance) {
  const auto result = testing::run_clmarch({"check", source_path("scenes/torus.yaml").string(), "--size", "64x36", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err << result.out;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  EXPECT_TRUE(report["passed"].get<bool>());
  for (const char* key : {"mask_mismatch", "depth_abs", "depth_rel", "depth_in_epsilons", "steps_diff", "normal_angle_deg_p99", "color"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
}

}  // namespace
}  // namespace clmarch

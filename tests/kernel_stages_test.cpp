// render.stages: the kernels' stages (march loops, normals, shadow rays, a hit's shading and material)
// called rather than inlined, so that PoCL compiles a large scene's map() once per stage instead of
// once per place that evaluates the field (issue 41: a 20-primitive scene's first picture). A call
// changes where the code lives, never what it computes: every plane of every render is the inlined
// program's, bit for bit.
#include "codegen/kernel_source.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace clmarch {
namespace {

Scene with_stages(const std::string& yaml, const char* stages) {
  std::string text = yaml;
  const std::size_t at = text.find("STAGES");
  EXPECT_NE(at, std::string::npos);
  text.replace(at, 6, stages);
  return testing::scene_from_yaml(text);
}

void expect_called_stages_render_the_inlined_image(const std::string& yaml, const std::string& what, int lanes = 16) {
  OpenClOptions options;
  options.purpose = KernelPurpose::Buffers;
  options.lanes = lanes;
  const RenderResult inlined = render_opencl(with_stages(yaml, "inline"), options);
  const RenderResult called = render_opencl(with_stages(yaml, "called"), options);
  EXPECT_EQ(inlined.stats.stages, "inline") << what;
  EXPECT_EQ(called.stats.stages, lanes > 1 ? "called" : "inline") << what << ": one lane inlines every stage";
  const testing::PlaneComparison planes = testing::compare_planes(called.buffers, inlined.buffers);
  EXPECT_EQ(planes.differing, "") << what;
  EXPECT_GE(planes.compared, 5) << what;
}

// Every stage in one program: both marches (camera pair, mirror rays), soft shadows past the
// bounds, occlusion, reflections' shading, glow, fog, the layers and ids of --buffers.
const char* const kEveryStage =
    "camera: {position: [0, 1.5, 5], look_at: [0, 0.5, 0]}\n"
    "render: {width: 48, height: 32, max_distance: 30, stages: STAGES}\n"
    "sdf:\n  union:\n    - sphere: {center: [0, 0.6, 0], radius: 0.6, reflectivity: 0.4}\n"
    "    - smooth_union:\n        k: 0.2\n        children:\n"
    "          - box: {center: [1.2, 0.4, 0], half_size: [0.3, 0.4, 0.3], rotate: [0, 30, 0], color: [0.2, 0.5, "
    "0.9]}\n"
    "          - torus: {center: [-1.2, 0.3, 0], major_radius: 0.4, minor_radius: 0.12}\n"
    "    - plane: {normal: [0, 1, 0], offset: 0}\n"
    "lights: [{point: {position: [2, 3, 2]}}, {directional: {direction: [-1, 2, 1], intensity: 0.5}}]\n"
    "shading: {model: blinn_phong, ambient_occlusion: {}, shadows: {mode: soft}, reflections: 2, sky: {},\n"
    "          glow: {radius: 0.2}, fog: {density: 0.02}}\n";

TEST(KernelStages, CalledStagesRenderTheInlinedImage) {
  expect_called_stages_render_the_inlined_image(kEveryStage, "every stage");
  expect_called_stages_render_the_inlined_image(kEveryStage, "one lane", 1);
}

TEST(KernelStages, CalledUnderTheCellsTilingAndAntiAliasing) {
  expect_called_stages_render_the_inlined_image(
      "camera: {position: [0.5, 0.1, 0.0], look_at: [3.5, 1.4, 6.0]}\n"
      "render: {width: 48, height: 32, max_steps: 300, epsilon: 1.0e-3, max_distance: 30, stages: STAGES}\n"
      "tiling: {cell: [1, 1, 1], method: cells}\n"
      "sdf: {round_box: {center: [0.5, 0.5, 0.5], half_size: [0.2, 0.2, 0.2], radius: 0.1}}\n"
      "lights: [{point: {position: [2.5, 5.5, 8.0]}}]\n"
      "shading: {shadows: {mode: hard}}\n",
      "cells tiling");
  expect_called_stages_render_the_inlined_image(
      "render: {width: 40, height: 24, samples: 4, stages: STAGES}\n"
      "sdf: {union: [{sphere: {radius: 0.8}}, {box: {center: [1.2, 0, 0], half_size: [0.3, 0.3, 0.3]}}]}\n"
      "shading: {tone_map: reinhard}\n",
      "anti-aliased");
}

// auto calls the stages of a scene whose code is large: the 20 primitives of the preview's
// benchmark scene, not the torus.
TEST(KernelStages, AutoCallsTheStagesOfLargeScenes) {
  const KernelOptions shaded{KernelPurpose::Shaded, 16};
  const Scene large = load_scene_file(testing::source_path("scripts/benchmarks/preview_20_primitives.yaml"));
  const Scene small = load_scene_file(testing::source_path("scenes/torus.yaml"));
  EXPECT_EQ(large.render.stages, KernelStages::Auto);
  EXPECT_TRUE(calls_stages(large, program_scene_code(large, shaded)));
  EXPECT_FALSE(calls_stages(small, program_scene_code(small, shaded)));
  EXPECT_NE(generate_kernel_source(large, shaded).find("#define STAGES_CALLED\n"), std::string::npos);
  EXPECT_EQ(generate_kernel_source(small, shaded).find("#define STAGES_CALLED"), std::string::npos);
  EXPECT_NE(program_key(large, shaded), program_key(with_stages(kEveryStage, "inline"), shaded));
  const Scene forced = with_stages(kEveryStage, "called");
  const Scene inlined = with_stages(kEveryStage, "inline");
  EXPECT_NE(program_key(forced, shaded), program_key(inlined, shaded)) << "the define is part of the key";
}

TEST(KernelStages, TheKeyTakesAutoInlineOrCalledAndStatsSayWhich) {
  EXPECT_EQ(testing::error_of("render: {stages: sometimes}\nsdf: {sphere: {}}\n"),
            "s.yaml:1:18: render.stages must be one of auto, inline, called (got 'sometimes')");
  testing::TempDir dir;
  const std::string scene = (dir / "s.yaml").string();
  {
    std::ofstream out(scene);
    out << "render: {width: 16, height: 8}\nsdf: {sphere: {radius: 0.8}}\n";
  }
  for (const char* stages : {"inline", "called"}) {
    const auto result = testing::run_clmarch(
        {"render", scene, "--no-image", "--stats", "--set", std::string("render.stages=") + stages});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find(fmt::format("\"stages\":\"{}\"", stages)), std::string::npos) << result.out;
  }
}

}  // namespace
}  // namespace clmarch

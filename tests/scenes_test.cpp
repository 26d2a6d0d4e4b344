// Every scene shipped in scenes/ (enumerated, so a new scene is covered the day it is added): it
// loads, its generated program compiles without a single compiler warning for every purpose and
// packet width, its buffers hold no NaN or Inf and agree across packet widths, and it passes the
// cross-check against the double reference with one and sixteen lanes (one test, so that the
// renders share their programs in one process rather than compiling them in two at once).
#include "check/cross_check.hpp"
#include "cl/device_program.hpp"
#include "codegen/kernel_source.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace clmarch {
namespace {

Scene load_small(const std::string& name) {
  Scene scene = load_scene_file(testing::source_path("scenes/" + name).string());
  scene.render.width = 64;
  scene.render.height = 36;
  return scene;
}

/// Most iterations of a Mandelbulb in the tree (0 without one).
int mandelbulb_iterations(const Node& node) {
  int most = node.kind == NodeKind::Mandelbulb ? std::get<Mandelbulb>(node.params).iterations : 0;
  for (const Node& child : node.children) most = std::max(most, mandelbulb_iterations(child));
  return most;
}

/// How far the colors of packet widths 1 and 16 may differ. The same operations run per lane in
/// both shapes, so colors agree to float rounding (1e-4), except where the field itself goes through
/// transcendental builtins whose scalar and vector versions round differently: each Mandelbulb
/// iteration may move the field by a few ulps (4u, u = 2^-24, at the orbit's magnitude ~1), the
/// normal's finite differences divide that by h (sqrt(3) delta / h), and the color moves with the
/// normal at most at the rate of the lights' total intensity.
double color_tolerance(const Scene& scene) {
  const double delta = 4.0 * std::ldexp(1.0, -24) * mandelbulb_iterations(scene.sdf);
  double intensity = 0.0;
  for (const Light& light : scene.lights)
    intensity += light.intensity * std::max({light.color.r, light.color.g, light.color.b});
  return 1e-4 + intensity * std::sqrt(3.0) * delta / scene.render.normal_epsilon;
}

TEST(BuildLog, WarningsInAnyCaseButNvidiasNoteOnKernels) {
  EXPECT_EQ(testing::compiler_warnings(""), "");
  EXPECT_EQ(
      testing::compiler_warnings("<kernel>:3:1: warning: unused variable 'x'\n  int x;\n  ^\n1 warning generated.\n"),
      "<kernel>:3:1: warning: unused variable 'x'\n1 warning generated.\n");
  EXPECT_EQ(testing::compiler_warnings("(): Warning: Function march is a kernel, so overriding noinline attribute. "
                                       "The function may be inlined when called.\n"),
            "");
  EXPECT_EQ(testing::compiler_warnings("ptxas Warning: stack size\n"), "ptxas Warning: stack size\n");
}

// The front end's check finds a warning clang gives by default, and a clean source has none.
TEST(BuildLog, TheFrontEndsWarningsAreSeen) {
  EXPECT_NE(testing::front_end_warnings("kernel void k(global int* out) { out[0] = 1.5f; }\n"), "");
  EXPECT_EQ(testing::front_end_warnings("kernel void k(global int* out) { out[0] = 1; }\n"), "");
  EXPECT_NE(testing::front_end_warnings("kernel void k(global int* out) { out[0] = ; }\n").find("does not compile"),
            std::string::npos);
}

class ShippedScene : public ::testing::TestWithParam<std::string> {};

// The front end's warnings (the program's build adds no warnings of its own; linking is the other
// tests' renders' part).
TEST_P(ShippedScene, CompilesWithoutWarnings) {
  const Scene scene = load_small(GetParam());
  for (KernelPurpose purpose : {KernelPurpose::DepthSteps, KernelPurpose::Normals, KernelPurpose::Shaded,
                                KernelPurpose::Buffers, KernelPurpose::EvalPoints}) {
    for (int lanes : {1, 16}) {
      EXPECT_EQ(testing::front_end_warnings(generate_kernel_source(scene, {purpose, lanes})), "")
          << "purpose " << static_cast<int>(purpose) << " lanes " << lanes;
    }
  }
}

TEST_P(ShippedScene, FiniteBuffersThatAgreeAcrossPacketWidthsAndPassTheCheck) {
  const Scene scene = load_small(GetParam());
  {
    SCOPED_TRACE("the cross-check at 96x54");
    Scene checked = scene;
    checked.render.width = 96;
    checked.render.height = 54;
    const FrameBuffers reference = render_reference(checked);
    for (int lanes : {1, 16}) {
      OpenClOptions options;
      options.lanes = lanes;
      const FrameBuffers opencl = render_opencl(checked, options).buffers;
      const CheckReport report = cross_check(checked, opencl, reference, reshade_hits(checked, opencl));
      EXPECT_TRUE(report.passed()) << "lanes " << lanes << "\n" << report.to_text();
      EXPECT_GT(report.both_hit, 0);
    }
  }
  OpenClOptions scalar_options, packet_options;
  scalar_options.lanes = 1;
  packet_options.lanes = 16;
  const FrameBuffers scalar = render_opencl(scene, scalar_options).buffers;
  const FrameBuffers packet = render_opencl(scene, packet_options).buffers;
  int hits = 0, mask_differences = 0;
  const double color_error = color_tolerance(scene);
  for (int j = 0; j < scene.render.height; ++j) {
    for (int i = 0; i < scene.render.width; ++i) {
      for (Channel c : {Channel::R, Channel::G, Channel::B, Channel::Steps, Channel::NX, Channel::NY, Channel::NZ}) {
        ASSERT_TRUE(std::isfinite(packet.at(c, i, j))) << kChannelNames[static_cast<int>(c)] << " at " << i << "," << j;
      }
      const float d1 = scalar.at(Channel::Depth, i, j), d16 = packet.at(Channel::Depth, i, j);
      ASSERT_FALSE(std::isnan(d16));
      ASSERT_TRUE(std::isfinite(d16) || d16 > 0.0f) << "depth is a distance or +inf";
      if (std::isfinite(d1) != std::isfinite(d16)) {
        ++mask_differences;
        continue;
      }
      if (!std::isfinite(d1)) continue;
      ++hits;
      // The same operations run per lane in both shapes; only the vector builtins' rounding may
      // differ, by a few ulps.
      EXPECT_NEAR(d1, d16, 1e-5 * (1.0 + d1)) << i << "," << j;
      EXPECT_NEAR(scalar.at(Channel::R, i, j), packet.at(Channel::R, i, j), color_error) << i << "," << j;
    }
  }
  EXPECT_GT(hits, 0) << "the scene shows nothing at this size";
  EXPECT_LE(mask_differences, 2) << "hit masks of packet widths 1 and 16 differ";
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(testing::shipped_scene_names()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                           return name;
                         });

}  // namespace
}  // namespace clmarch

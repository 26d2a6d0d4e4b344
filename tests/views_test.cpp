// The debug views (shading.view) against their definitions in docs/scene-format.md, on buffers
// whose values are chosen by hand.
#include "frame/views.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace clmarch {
namespace {

constexpr float kMiss = INFINITY;

/// Four pixels: hits at depths 2, 6 and 4, and a miss; steps 10, 40, 64 and 5; a color already
/// in R, G, B that every view but shaded must replace.
FrameBuffers four_pixels() {
  FrameBuffers b(2, 2);
  b.plane(Channel::Depth) = {2.0f, 6.0f, kMiss, 4.0f};
  b.plane(Channel::Steps) = {10.0f, 40.0f, 64.0f, 5.0f};
  b.plane(Channel::NX) = {1.0f, 0.0f, 0.0f, -0.6f};
  b.plane(Channel::NY) = {0.0f, -1.0f, 0.0f, 0.8f};
  b.plane(Channel::NZ) = {0.0f, 0.0f, 0.0f, 0.0f};
  for (Channel c : {Channel::R, Channel::G, Channel::B}) b.plane(c) = {0.3f, 0.3f, 0.3f, 0.3f};
  return b;
}

void expect_gray(const FrameBuffers& b, const std::vector<float>& expected) {
  for (std::size_t i = 0; i < expected.size(); ++i) {
    for (Channel c : {Channel::R, Channel::G, Channel::B}) {
      EXPECT_FLOAT_EQ(b.plane(c)[i], expected[i]) << "pixel " << i << " channel " << static_cast<int>(c);
    }
  }
}

TEST(DebugViews, DepthIsOneAtTheNearestHitAndPointTwoAtTheFarthestAndBlackOnMisses) {
  FrameBuffers b = four_pixels();
  apply_view(b, View::Depth, RenderSettings{});
  // 1 - 0.8 * (depth - 2) / (6 - 2)
  expect_gray(b, {1.0f, 0.2f, 0.0f, 0.6f});
}

TEST(DebugViews, DepthOfASingleHitDepthIsOne) {
  FrameBuffers b = four_pixels();
  b.plane(Channel::Depth) = {3.0f, kMiss, 3.0f, kMiss};
  apply_view(b, View::Depth, RenderSettings{});
  expect_gray(b, {1.0f, 0.0f, 1.0f, 0.0f});
}

TEST(DebugViews, StepsAreTheFractionOfMaxStepsOnHitsAndMissesAlike) {
  FrameBuffers b = four_pixels();
  RenderSettings settings;
  settings.max_steps = 64;
  apply_view(b, View::Steps, settings);
  expect_gray(b, {10.0f / 64.0f, 40.0f / 64.0f, 1.0f, 5.0f / 64.0f});
}

TEST(DebugViews, NormalsMapToHalfPlusHalfAndMissesToBlack) {
  FrameBuffers b = four_pixels();
  apply_view(b, View::Normals, RenderSettings{});
  const std::vector<float> r = {1.0f, 0.5f, 0.0f, 0.2f}, g = {0.5f, 0.0f, 0.0f, 0.9f}, bl = {0.5f, 0.5f, 0.0f, 0.5f};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_FLOAT_EQ(b.plane(Channel::R)[i], r[i]) << i;
    EXPECT_FLOAT_EQ(b.plane(Channel::G)[i], g[i]) << i;
    EXPECT_FLOAT_EQ(b.plane(Channel::B)[i], bl[i]) << i;
  }
}

TEST(DebugViews, ShadedKeepsTheColor) {
  FrameBuffers b = four_pixels();
  apply_view(b, View::Shaded, RenderSettings{});
  expect_gray(b, {0.3f, 0.3f, 0.3f, 0.3f});
}

}  // namespace
}  // namespace clmarch

// The torus scene against its golden image (tests/golden/torus.png, 96x54, made by
// scripts/update-golden.sh on purpose, never by the tests).
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace clmarch {
namespace {

using testing::read_image;
using testing::run_clmarch;
using testing::source_path;
using testing::TempDir;

// Interior pixels differ between devices and packet widths only by float rounding (< 1e-4 in
// linear color): at most one 8-bit step after sRGB encoding.
constexpr float kInteriorTolerance = 1.0f / 255.0f + 1e-6f;
// Silhouette pixels may flip between hit and miss when a ray grazes the surface within float
// rounding; the 96x54 torus has ~300 silhouette pixels, a handful of flips is allowed.
constexpr int kMaxDifferingPixels = 8;

TEST(GoldenImage, TorusMatches) {
  for (const char* lanes : {"1", "16"}) {
    TempDir dir;
    const auto result = run_clmarch({"render", source_path("scenes/torus.yaml").string(), "--size", "96x54", "--lanes", lanes,
                                     "-o", (dir / "torus.png").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const testing::Image image = read_image(dir / "torus.png");
    const testing::Image golden = read_image(source_path("tests/golden/torus.png"));
    ASSERT_EQ(image.width, golden.width);
    ASSERT_EQ(image.height, golden.height);
    int differing = 0;
    double lit = 0.0;
    for (int j = 0; j < image.height; ++j) {
      for (int i = 0; i < image.width; ++i) {
        bool differs = false;
        for (int c = 0; c < 3; ++c) {
          differs = differs || std::abs(image.at(i, j, c) - golden.at(i, j, c)) > kInteriorTolerance;
          lit += golden.at(i, j, c);
        }
        differing += differs;
      }
    }
    EXPECT_LE(differing, kMaxDifferingPixels) << "lanes " << lanes;
    EXPECT_GT(lit, 100.0) << "the golden image must not be black";
  }
}

}  // namespace
}  // namespace clmarch

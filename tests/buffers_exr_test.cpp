// The --buffers EXR: its channel names are a contract (R, G, B, depth, steps, N.x, N.y, N.z) and
// its values follow the documented rules (linear color, +inf depth on a miss, unit normals).
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>

namespace clmarch {
namespace {

TEST(BuffersExr, ChannelsAndValuesFollowTheContract) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {radius: 1}}\ncamera: {position: [0, 0, 5]}\nrender: {width: 32, height: 24}\n";
  for (const char* backend : {"opencl", "reference"}) {
    const auto result = testing::run_clmarch({"render", (dir / "scene.yaml").string(), "--backend", backend, "-o",
                                              (dir / "c.exr").string(), "--buffers", (dir / "b.exr").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    auto in = OIIO::ImageInput::open((dir / "b.exr").string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    std::vector<std::string> names(spec.channelnames.begin(), spec.channelnames.end());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "N.x", "N.y", "N.z", "R", "depth", "steps"}));
    const auto channel = [&](const char* name) { return spec.channelindex(name); };
    const testing::Image image = testing::read_image(dir / "b.exr");
    // The corner misses the sphere, the centre hits it head-on at distance 4. The corner's ray
    // misses the scene's bounding sphere, so it takes no step (render.bounds: sphere).
    EXPECT_TRUE(std::isinf(image.at(0, 0, channel("depth"))));
    EXPECT_EQ(image.at(0, 0, channel("steps")), 0.0f);
    EXPECT_GE(image.at(16, 12, channel("steps")), 1.0f);
    // Pixel centres sit half a pixel off the axis: depth 4 within that offset.
    EXPECT_NEAR(image.at(16, 12, channel("depth")), 4.0, 0.01);
    EXPECT_NEAR(image.at(16, 12, channel("N.z")), 1.0, 1e-2);
    const float nx = image.at(14, 11, channel("N.x")), ny = image.at(14, 11, channel("N.y")), nz = image.at(14, 11, channel("N.z"));
    EXPECT_NEAR(std::sqrt(nx * nx + ny * ny + nz * nz), 1.0, 1e-4) << backend;
    // The color EXR is linear: the same values as the buffers' R, G, B.
    const testing::Image color = testing::read_image(dir / "c.exr");
    EXPECT_EQ(color.at(16, 12, 0), image.at(16, 12, channel("R")));
  }
}

}  // namespace
}  // namespace clmarch

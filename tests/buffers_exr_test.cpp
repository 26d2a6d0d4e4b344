// The --buffers EXR: its channel names are a contract (R, G, B, depth, steps, N.x, N.y, N.z, then
// A, Z, samples, id, the layers ao, diffuse and specular, P.x, P.y, P.z) and its values follow the documented rules
// (linear color, +inf depth on a miss, unit normals, coverage, the camera in the header).
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>

namespace clmarch {
namespace {

// render.precision: double adds depth.lo (issue 26): depth + depth.lo in double is the double
// depth. 1e-4 from a unit sphere, the float depth holds the hit to 1e-12 (half its spacing) and
// the pair to the march's epsilon, 1e-14, on both backends.
TEST(BuffersExr, DoubleRendersAddTheDepthsRemainder) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml")
      << "sdf: {sphere: {radius: 1}}\ncamera: {position: [0, 0, 1.0001], look_at: [0, 0, 0], fov: 0.001}\n"
         "render: {width: 8, height: 6, precision: double, epsilon: 1.0e-14, normal_epsilon: 1.0e-9}\n";
  for (const char* backend : {"opencl", "reference"}) {
    SCOPED_TRACE(backend);
    const auto result = testing::run_clmarch({"render", (dir / "scene.yaml").string(), "--backend", backend, "-o",
                                              (dir / "c.exr").string(), "--buffers", (dir / "b.exr").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    auto in = OIIO::ImageInput::open((dir / "b.exr").string());
    ASSERT_TRUE(in);
    const int lo = in->spec().channelindex("depth.lo"), depth = in->spec().channelindex("depth");
    ASSERT_GE(lo, 0) << "no depth.lo channel";
    const testing::Image image = testing::read_image(dir / "b.exr");
    // Pixel (4, 3)'s ray is 3e-8 radians off the axis: its hit is 1e-4 away to 1e-15.
    const double t = static_cast<double>(image.at(4, 3, depth)) + image.at(4, 3, lo);
    EXPECT_NEAR(t, 1e-4, 2e-14);
    EXPECT_NE(image.at(4, 3, lo), 0.0f);
  }
  std::ofstream(dir / "scene.yaml")
      << "sdf: {sphere: {radius: 1}}\ncamera: {position: [0, 0, 5]}\nrender: {width: 8, height: 6}\n";
  ASSERT_EQ(testing::run_clmarch({"render", (dir / "scene.yaml").string(), "-o", (dir / "c.exr").string(), "--buffers",
                                  (dir / "b.exr").string()})
                .exit_code,
            0);
  auto in = OIIO::ImageInput::open((dir / "b.exr").string());
  ASSERT_TRUE(in);
  EXPECT_LT(in->spec().channelindex("depth.lo"), 0) << "float renders keep their 25 channels";
}

TEST(BuffersExr, ChannelsAndValuesFollowTheContract) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml")
      << "sdf: {sphere: {radius: 1}}\ncamera: {position: [0, 0, 5]}\nrender: {width: 32, height: 24}\n";
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
    EXPECT_EQ(names, (std::vector<std::string>{"A",          "B",          "G",          "N.x",    "N.y",
                                               "N.z",        "P.x",        "P.y",        "P.z",    "R",
                                               "Z",          "ao.B",       "ao.G",       "ao.R",   "depth",
                                               "diffuse.B",  "diffuse.G",  "diffuse.R",  "id",     "samples",
                                               "specular.B", "specular.G", "specular.R", "status", "steps"}));
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
    const float nx = image.at(14, 11, channel("N.x")), ny = image.at(14, 11, channel("N.y")),
                nz = image.at(14, 11, channel("N.z"));
    EXPECT_NEAR(std::sqrt(nx * nx + ny * ny + nz * nz), 1.0, 1e-4) << backend;
    // A is the coverage of the one ray per pixel; Z is depth; P the hit in the world; the camera
    // in the header: worldToCamera takes P to (0, 0, -4)-ish in front of the camera.
    EXPECT_EQ(image.at(16, 12, channel("A")), 1.0f);
    EXPECT_EQ(image.at(0, 0, channel("A")), 0.0f);
    EXPECT_EQ(image.at(16, 12, channel("Z")), image.at(16, 12, channel("depth")));
    EXPECT_TRUE(std::isinf(image.at(0, 0, channel("Z"))));
    EXPECT_EQ(image.at(16, 12, channel("samples")), 1.0f);
    // The centre ray hit; the corner's missed the scene's bounding sphere (the status channel).
    EXPECT_EQ(image.at(16, 12, channel("status")), 1.0f);
    EXPECT_EQ(image.at(0, 0, channel("status")), 0.0f);
    // The scene's one primitive is number 0; a miss is -1.
    EXPECT_EQ(image.at(16, 12, channel("id")), 0.0f);
    EXPECT_EQ(image.at(0, 0, channel("id")), -1.0f);
    // P lies on the unit sphere, depth away from the camera at (0, 0, 5).
    const double px = image.at(16, 12, channel("P.x")), py = image.at(16, 12, channel("P.y")),
                 pz = image.at(16, 12, channel("P.z"));
    EXPECT_NEAR(std::sqrt(px * px + py * py + pz * pz), 1.0, 1e-3);
    EXPECT_NEAR(std::sqrt(px * px + py * py + (pz - 5.0) * (pz - 5.0)), image.at(16, 12, channel("depth")), 1e-5);
    EXPECT_EQ(image.at(0, 0, channel("P.y")), 0.0f);
    const OIIO::ParamValue* to_camera = spec.find_attribute("worldToCamera", OIIO::TypeMatrix44);
    const OIIO::ParamValue* to_ndc = spec.find_attribute("worldToNDC", OIIO::TypeMatrix44);
    ASSERT_TRUE(to_camera) << backend;
    ASSERT_TRUE(to_ndc) << backend;
    const float* m = static_cast<const float*>(to_camera->data());
    // The world point (0, 0, 1) in camera space, p M with p = (0, 0, 1, 1): camera at z = 5 looking
    // down -z, so 4 in front of it, z = -4.
    EXPECT_NEAR(m[2 * 4 + 2] + m[3 * 4 + 2], -4.0, 1e-5);
    const float* n = static_cast<const float*>(to_ndc->data());
    // The point (1, 0, 1) projects to x = (1 / 4) / tan(fov / 2) / aspect, w = 4.
    const double w = n[2 * 4 + 3] + n[3 * 4 + 3] + n[0 * 4 + 3];
    const double x = n[0 * 4 + 0] + n[2 * 4 + 0] + n[3 * 4 + 0];
    EXPECT_NEAR(w, 4.0, 1e-5);
    EXPECT_NEAR(x / w, 0.25 / std::tan(std::acos(-1.0) / 8.0) / (32.0 / 24.0), 1e-5);
    EXPECT_EQ(spec.get_string_attribute("clmarch:camera.position"), "[0, 0, 5]");
    // The color EXR is linear: the same values as the buffers' R, G, B.
    const testing::Image color = testing::read_image(dir / "c.exr");
    EXPECT_EQ(color.at(16, 12, 0), image.at(16, 12, channel("R")));
  }
}

}  // namespace
}  // namespace clmarch

// render.precision (issue 26): a scene renders in double end to end on the device (camera, march,
// distance function, normals, shading), so that a deep zoom finer than float's spacing shows its
// structure and passes the check against the reference, where float is flat noise that the check
// now refuses as beyond its reach; the key's bad values and the devices that cannot run double.
#include "check/cross_check.hpp"
#include "common/errors.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "render/prepared_program.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <tuple>

namespace clmarch {
namespace {

using testing::source_path;

/// The deep zoom of scenes/zoom/mandelbulb_deep.yaml (pixels 5.5e-9 apart at 640 x 360; here at
/// 64 x 36, 5.5e-8: still below float's spacing of 6e-8 at the surface), in the given precision.
Scene deep_zoom(Precision precision) {
  Scene scene = load_scene_file(source_path("scenes/zoom/mandelbulb_deep.yaml").string());
  scene.render.width = 64;
  scene.render.height = 36;
  scene.render.precision = precision;
  return scene;
}

/// Distinct normals among the pixels hit: a view with structure has nearly one per pixel.
std::size_t distinct_normals(const FrameBuffers& b) {
  std::set<std::tuple<float, float, float>> normals;
  for (int j = 0; j < b.height; ++j) {
    for (int i = 0; i < b.width; ++i) {
      if (std::isfinite(b.at(Channel::Depth, i, j)))
        normals.emplace(b.at(Channel::NX, i, j), b.at(Channel::NY, i, j), b.at(Channel::NZ, i, j));
    }
  }
  return normals.size();
}

// In double the deep zoom shows the bulb's folds and passes the check, at one pixel a work-item
// (GPUs' shape, where the kernels' float literals in builtins are taken as double: kernels/lanes.cl)
// as at 16.
TEST(DeepZoom, DoubleShowsTheStructureAndPassesTheCheck) {
  const Scene scene = deep_zoom(Precision::Double);
  const FrameBuffers reference = render_reference(scene);
  FrameBuffers opencl;
  for (int lanes : {1, 16}) {
    SCOPED_TRACE(fmt::format("{} lanes", lanes));
    OpenClOptions options;
    options.purpose = KernelPurpose::Buffers;
    options.lanes = lanes;
    opencl = render_opencl(scene, options).buffers;
    const CheckReport report = cross_check(scene, opencl, reference, reshade_hits(scene, opencl));
    EXPECT_TRUE(report.passed()) << report.to_text();
    EXPECT_GT(report.both_hit, 64 * 36 * 9 / 10);
  }
  EXPECT_GT(distinct_normals(opencl), static_cast<std::size_t>(64 * 36 / 2));
  // Structure, not a plane: the normals turn by tens of degrees across the view.
  double widest = 0.0;
  const glm::dvec3 first(opencl.at(Channel::NX, 0, 0), opencl.at(Channel::NY, 0, 0), opencl.at(Channel::NZ, 0, 0));
  for (int j = 0; j < opencl.height; ++j) {
    for (int i = 0; i < opencl.width; ++i) {
      const glm::dvec3 n(opencl.at(Channel::NX, i, j), opencl.at(Channel::NY, i, j), opencl.at(Channel::NZ, i, j));
      widest = std::max(widest, std::acos(std::clamp(glm::dot(first, n), -1.0, 1.0)));
    }
  }
  EXPECT_GT(widest, 20.0 * M_PI / 180.0);
}

// The zoom sequence's shallow end (scripts/zoom-sequence.sh at D = 0.2: the camera 0.2 from the
// same point, epsilon and normal_epsilon 1e-6) passes in double too. The two renders' hit points
// agree to about 1e-12 of their depth, but both buffers hold depth as float: the check allows the
// float rounding of both (kDepthBufferRounding). Without it the normal tolerance assumed the hit
// points known to double's rounding and this frame failed, its normals 0.0002 degrees apart
// against a tolerance 635 times smaller (64 x 36).
TEST(DeepZoom, TheShallowEndPassesInDoubleToo) {
  Scene scene = deep_zoom(Precision::Double);
  const glm::dvec3 hit = scene.camera.look_at;
  scene.camera.position = hit - 0.2 * glm::normalize(hit - scene.camera.position);
  scene.render.epsilon = scene.render.normal_epsilon = 1e-6;
  scene.render.max_distance = 10.0;
  OpenClOptions options;
  options.purpose = KernelPurpose::Buffers;
  const FrameBuffers opencl = render_opencl(scene, options).buffers;
  const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
  EXPECT_TRUE(report.passed()) << report.to_text();
  EXPECT_GT(report.both_hit, 64 * 36 / 2);
}

// The same view in float: its rays start from the same rounded camera and march through the same
// rounded points, so their normals' taps land on the same few points (few distinct normals: a
// flat image), and the check says the scene is beyond float's reach
// (its normal tolerance would pass any normal) and points to double.
TEST(DeepZoom, FloatIsBeyondItsReachAndTheCheckSaysSo) {
  const Scene scene = deep_zoom(Precision::Float);
  OpenClOptions options;
  options.purpose = KernelPurpose::Buffers;
  const FrameBuffers opencl = render_opencl(scene, options).buffers;
  EXPECT_LT(distinct_normals(opencl), static_cast<std::size_t>(64 * 36 / 10));
  const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
  ASSERT_FALSE(report.passed());
  const bool beyond = std::any_of(report.failures.begin(), report.failures.end(), [](const std::string& f) {
    return f.find("exceeds pi") != std::string::npos && f.find("render.precision: double") != std::string::npos;
  });
  EXPECT_TRUE(beyond) << report.to_text();
}

// A check whose normal tolerance outgrows the angles' range checks nothing: the reference against
// itself, a float render with a normal step far below float's spacing, fails on that alone.
TEST(CheckRange, ANormalToleranceBeyondPiFails) {
  Scene scene = load_scene_file(source_path("scenes/torus.yaml").string());
  scene.render.width = 48;
  scene.render.height = 27;
  const FrameBuffers reference = render_reference(scene);
  EXPECT_TRUE(cross_check(scene, reference, reference).passed());
  scene.render.normal_epsilon = 1e-12;
  const CheckReport report = cross_check(scene, reference, reference);
  ASSERT_EQ(report.failures.size(), 1u) << report.to_text();
  EXPECT_NE(report.failures[0].find("the normal tolerance exceeds pi at"), std::string::npos) << report.to_text();
  EXPECT_EQ(report.normal_tolerance_past_pi, report.both_hit);
}

// A render whose depths are wrong fails on its depths, and where its normal tolerance passes pi
// because of them, on that, but it is not called beyond the precision's reach: only rounding's
// share of the normal tolerance counts for that.
TEST(CheckRange, AWrongDepthIsNotBlamedOnThePrecision) {
  Scene scene = load_scene_file(source_path("scenes/torus.yaml").string());
  scene.render.width = 48;
  scene.render.height = 27;
  const FrameBuffers reference = render_reference(scene);
  FrameBuffers shifted = reference;
  for (float& t : shifted.plane(Channel::Depth)) t += 10.0f * static_cast<float>(scene.render.normal_epsilon) * 4.0f;
  const CheckReport report = cross_check(scene, shifted, reference);
  EXPECT_FALSE(report.passed());
  EXPECT_EQ(report.normal_rounding_past_pi, 0) << report.to_text();
  EXPECT_EQ(report.to_text().find("reach"), std::string::npos) << report.to_text();
  EXPECT_NE(report.to_text().find("depth error p99"), std::string::npos) << report.to_text();
  // Depths 1000 normal steps apart: every normal tolerance passes pi, and the check says why.
  for (float& t : shifted.plane(Channel::Depth)) t += 1000.0f * static_cast<float>(scene.render.normal_epsilon);
  const CheckReport far_apart = cross_check(scene, shifted, reference);
  EXPECT_EQ(far_apart.normal_tolerance_past_pi, far_apart.both_hit);
  EXPECT_NE(far_apart.to_text().find("depths differ by up to"), std::string::npos) << far_apart.to_text();
}

// Every shipped scene builds and renders in double at one pixel a work-item (the GPUs' shape),
// where the kernels' builtins called with float literals take double arguments (kernels/lanes.cl),
// every colour finite. (16 lanes in double: the stress suite renders every scene in both precisions.)
TEST(Precision, EveryShippedSceneRendersInDoubleAtOneLane) {
  for (const std::string& name : testing::shipped_scene_names()) {
    SCOPED_TRACE(name);
    Scene scene = load_scene_file(source_path("scenes/" + name).string());
    scene.render.width = 16;
    scene.render.height = 9;
    scene.render.precision = Precision::Double;
    OpenClOptions options;
    options.lanes = 1;
    const FrameBuffers buffers = render_opencl(scene, options).buffers;
    int finite = 0;
    for (float v : buffers.plane(Channel::R)) finite += std::isfinite(v);
    EXPECT_EQ(finite, 16 * 9);
  }
}

TEST(Precision, DevicesWithoutDoubleAreOneLineErrors) {
  Scene scene = testing::scene_from_yaml("sdf: {sphere: {}}\nrender: {precision: double}\n");
  scene.source_name = "zoom.yaml";
  const KernelVariant variant = scene_variant(scene, {});
  EXPECT_NO_THROW(check_precision_support(scene, variant, "GPU (NVIDIA CUDA)", true));
  try {
    check_precision_support(scene, variant, "Tiny GPU (Vendor)", false);
    ADD_FAILURE() << "a device without cl_khr_fp64 was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "zoom.yaml: render.precision: double needs a device with cl_khr_fp64 (double arithmetic), which Tiny GPU "
              "(Vendor) lacks; choose another device (clmarch devices) or render.precision: float");
  }
  scene.render.precision = Precision::Float;
  EXPECT_NO_THROW(check_precision_support(scene, scene_variant(scene, {}), "Tiny GPU (Vendor)", false));
}

// --stats says which arithmetic ran, and a double program on the CPU keeps its vector lanes.
TEST(Precision, StatsSayWhichArithmeticRan) {
  testing::TempDir dir;
  const std::string scene = (dir / "scene.yaml").string();
  std::ofstream(scene) << "sdf: {sphere: {}}\nrender: {width: 16, height: 9}\n";
  for (const char* precision : {"float", "double"}) {
    const testing::CommandResult r =
        testing::run_clmarch({"render", scene, "--set", std::string("render.precision=") + precision, "--stats", "-o",
                              (dir / "out.png").string()});
    ASSERT_EQ(r.exit_code, kExitOk) << r.err;
    const nlohmann::json stats = nlohmann::json::parse(r.out);
    EXPECT_EQ(stats["precision"], precision);
    EXPECT_GT(stats["lanes"].get<int>(), 1) << "PoCL's default lanes";
  }
}

// Through the executable: one line naming the file position or --set, exit 2, no image.
TEST(Precision, BadValuesAreOneLineErrors) {
  testing::TempDir dir;
  const std::string scene = (dir / "scene.yaml").string();
  const std::string out = (dir / "out.png").string();
  std::ofstream(scene) << "sdf: {sphere: {}}\nrender: {width: 8, height: 8, precision: half}\n";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"render", scene, "-o", out}, "scene.yaml:2:42: render.precision must be one of float, double (got 'half')"},
      {{"render", scene, "--set", "render.precision=64", "-o", out},
       "render.precision must be one of float, double (got '64')"},
  };
  for (const auto& [args, message] : cases) {
    const testing::CommandResult r = testing::run_clmarch(args);
    EXPECT_EQ(r.exit_code, kExitBadInput) << message;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

}  // namespace
}  // namespace clmarch

// The cross-check (every shipped scene passes it: scenes_test.cpp, beside the scene's other renders):
// features no shipped scene uses (shadows under the cells tiling, two reflection bounces); it has teeth: a
// perturbed OpenCL render fails it while the unperturbed one passes, and each criterion fails just
// past its per-pixel tolerance and passes within it.
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

namespace clmarch {
namespace {

using testing::source_path;
using testing::TempDir;

Scene small_scene(const std::string& name, const std::vector<SceneOverride>& overrides = {}) {
  Scene scene = load_scene_file(source_path("scenes/" + name).string(), overrides);
  scene.render.width = 96;
  scene.render.height = 54;
  return scene;
}

/// Renders opencl_scene on the device and scene on the reference, and compares them as `clmarch
/// check` does, the shading of the device's own hits included.
CheckReport check_against(const Scene& scene, const Scene& opencl_scene, int lanes = 16) {
  OpenClOptions options;
  options.lanes = lanes;
  const FrameBuffers opencl = render_opencl(opencl_scene, options).buffers;
  return cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
}

// Shadow rays under the cells tiling start at min_t past the surface: the only rays of that march
// with a start other than 0 (the cone pass is off with cells). No shipped tiled scene has shadows.
// The Sierpinski tetrahedron (issue 25) at the IFS scales 2 and 3, in float and in double, over a
// checkered floor with soft shadows: the device agrees with the reference.
TEST(CheckFeatures, TheSierpinskiTetrahedron) {
  for (const char* scale : {"2", "3"}) {
    for (const char* precision : {"float", "double"}) {
      const Scene scene = testing::scene_from_yaml(
          std::string("camera: {position: [2.2, 1.6, 2.6], look_at: [0, -0.1, 0], fov: 45}\n"
                      "render: {width: 96, height: 54, max_steps: 300, precision: ") +
          precision +
          "}\n"
          "sdf: {union: [{sierpinski: {size: 1, iterations: 8, scale: " +
          scale +
          ", step_factor: 0.8}},\n"
          "              {plane: {normal: [0, 1, 0], offset: 1.2}}]}\n"
          "lights: [{directional: {direction: [1, 2, 1]}}]\nshading: {ambient: 0.2, shadows: {mode: soft}}\n");
      const CheckReport report = check_against(scene, scene);
      EXPECT_TRUE(report.passed()) << "scale " << scale << " " << precision << "\n" << report.to_text();
      EXPECT_GT(report.both_hit, 500);
    }
  }
}

// The Mandelbox at a negative and a positive scale and the quaternion Julia set (issue 25), in float
// and double, over a floor with soft shadows: the device agrees with the reference.
TEST(CheckFeatures, TheMandelboxAndTheJuliaSet) {
  const char* fractals[] = {"mandelbox: {scale: -1.5, iterations: 10, step_factor: 0.8}",
                            "mandelbox: {scale: 2, iterations: 6, step_factor: 0.8}",
                            "julia: {c: [-0.2, 0.6, 0.2, 0.1], iterations: 10, step_factor: 0.8}"};
  const double distances[] = {5.5, 16.0, 3.2};
  for (int i = 0; i < 3; ++i) {
    for (const char* precision : {"float", "double"}) {
      const std::string floor = fmt::format("{{plane: {{normal: [0, 1, 0], offset: {}}}}}", distances[i] * 0.4);
      const Scene scene = testing::scene_from_yaml(fmt::format(
          "camera: {{position: [{0}, {1}, {0}], look_at: [0, 0, 0], fov: 45}}\n"
          "render: {{width: 96, height: 54, max_steps: 400, max_distance: {2}, precision: {3}}}\n"
          "sdf: {{union: [{{{4}}}, {5}]}}\n"
          "lights: [{{directional: {{direction: [1, 2, 1]}}}}]\nshading: {{ambient: 0.2, shadows: {{mode: soft}}}}\n",
          distances[i] * 0.6, distances[i] * 0.5, distances[i] * 4, precision, fractals[i], floor));
      const CheckReport report = check_against(scene, scene);
      EXPECT_TRUE(report.passed()) << fractals[i] << " " << precision << "\n" << report.to_text();
      EXPECT_GT(report.both_hit, 500) << fractals[i];
    }
  }
}

TEST(CheckFeatures, ShadowsUnderTheCellsTiling) {
  const Scene scene = small_scene("tiled_spheres.yaml", {{"shading.shadows", "{mode: soft, min_t: 0.3}"}});
  ASSERT_EQ(scene.tiling->method, TilingMethod::Cells);
  for (int lanes : {1, 16}) {
    const CheckReport report = check_against(scene, scene, lanes);
    EXPECT_TRUE(report.passed()) << "lanes " << lanes << "\n" << report.to_text();
  }
}

// Two mirror bounces: a bounce that misses shows the sky once and ends that pixel's bounces (the
// mirror floor's rays that leave past the torus must not bounce again off the same floor). No
// shipped scene has more than one bounce.
TEST(CheckFeatures, SecondBounceFollowsOnlyTheRaysWhoseFirstBounceHit) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 2.5, 4], look_at: [0, 0, 0], fov: 60}\n"
      "sdf:\n  union:\n    - torus: {color: [0.9, 0.3, 0.2], reflectivity: 0.6}\n"
      "    - plane: {normal: [0, 1, 0], offset: 0.6, color: [0.2, 0.2, 0.25], reflectivity: 0.8}\n"
      "render: {width: 64, height: 48}\nlights:\n  - directional: {direction: [1, 2, 1]}\n"
      "shading: {model: blinn_phong, reflections: 2}\n");
  const CheckReport report = check_against(scene, scene);
  EXPECT_TRUE(report.passed()) << report.to_text();
}

// The peak of the GGX distribution at the least roughness (0.02: a^2 = 1.6e-7), on every pixel:
// camera and light at the centre of a spherical metal cave, so n = v = l everywhere. In float,
// 1 - (n.h)^2 there keeps none of its digits unless taken as |n x h|^2 (the kernel's highlight was
// off by 0.56), the reference must renormalise the float normal it re-shades, and the end-to-end
// color tolerance must follow the distribution's slope at that roughness.
Scene metal_cave(const std::string& light, const std::string& shading) {
  return testing::scene_from_yaml(
      "camera: {position: [0, 0, 0], look_at: [0, 0, -1], fov: 60}\n"
      "render: {width: 48, height: 27, epsilon: 1.0e-4}\n"
      "sdf: {subtraction: [{box: {half_size: [10, 10, 10]}},"
      " {sphere: {radius: 5, color: [0.9, 0.8, 0.7], metallic: 1, roughness: 0.02}}]}\n"
      "lights: [{point: {position: [0, 0, 0], " +
      light +
      "}}]\n"
      "shading: " +
      shading + "\n");
}

TEST(CheckFeatures, ThePeakOfAnAlmostSmoothMetal) {
  const Scene scene = metal_cave("intensity: 1.0e-6", "{model: pbr, ambient: 0.03, tone_map: reinhard}");
  for (int lanes : {1, 16}) {
    const CheckReport report = check_against(scene, scene, lanes);
    EXPECT_TRUE(report.passed()) << "lanes " << lanes << "\n" << report.to_text();
    EXPECT_EQ(report.both_hit, 48 * 27);
    EXPECT_GT(report.color_max_abs, 0.1) << "the highlight is there, and the normals' float noise moves it";
  }
}

Scene fog_seen_from_above(const std::string& falloff) {
  return testing::scene_from_yaml(
      "camera: {position: [0, 100, 30], look_at: [0, 0, 0], fov: 40}\n"
      "render: {width: 48, height: 27, epsilon: 1.0e-4, max_distance: 300}\n"
      "sdf: {union: [{plane: {normal: [0, 1, 0], offset: 0, color: 0.8}},"
      " {sphere: {center: [0, 1, 0], radius: 1, color: [0.9, 0.3, 0.2]}}]}\n"
      "lights: [{directional: {direction: [-1, 2, 1]}}]\n"
      "shading: {model: lambert, height_fog: {density: 0.5, falloff: " +
      falloff + ", color: [0.5, 0.6, 0.7]}}\n");
}

// Where float's rounding is amplified, the shading's tolerance follows: a Phong highlight of
// shininess 16384 at its peak (the power multiplies the rounding of its base, some 1e-3 of the
// color here), and HDR colors of thousands without tone mapping (half an 8-bit step of the
// color's own size). And the height fog at its extremes: a falloff of 1e-6, whose 1 - exp(-x) the
// kernel must not take as a difference (it was 4.5 times the tolerance off), and a camera 100
// above the floor with falloff 1 and 10, where exp(-x) of a descending ray overflowed, float's
// from x < -88 (the whole image fog, or NaN) and double's from x < -709 (the reference's NaN).
TEST(CheckFeatures, AmplifiedRoundingAndHeightFogAtItsExtremes) {
  const std::vector<std::pair<std::string, Scene>> cases = {
      {"shininess 16384", metal_cave("intensity: 1", "{model: phong, specular: 1, shininess: 16384}")},
      {"HDR", small_scene("sphere_shadows.yaml", {{"lights.0.point.intensity", "5000"}})},
      {"falloff 1e-6", small_scene("moving_shapes.yaml", {{"shading.height_fog", "{density: 0.08, falloff: 1.0e-6}"}})},
      {"falloff 1 from above", fog_seen_from_above("1")},
      {"falloff 10 from above", fog_seen_from_above("10")}};
  for (const auto& [name, scene] : cases) {
    const CheckReport report = check_against(scene, scene);
    EXPECT_TRUE(report.passed()) << name << "\n" << report.to_text();
    EXPECT_GT(report.shading_max_abs, 0.0) << name;
  }
}

// The Mandelbulb's pole seen close up (power 5; the scene's rotation puts the pole on y): its
// polar angle taken as acos(z / r) lost its digits near the pole, and the power multiplied the
// error each iteration (normals 47 degrees off, depth past its tolerance); atan2(rho, z) keeps them.
TEST(CheckFeatures, TheMandelbulbsPoles) {
  for (const char* y : {"2.5", "-2.5"}) {
    const Scene scene =
        small_scene("mandelbulb.yaml",
                    {{"sdf.mandelbulb.power", "5"},
                     {"camera", fmt::format("{{position: [0, {}, 0], look_at: [0, 0, 0], up: [0, 0, 1], fov: 1}}", y)},
                     {"render.epsilon", "1e-4"},
                     {"render.normal_epsilon", "1e-4"}});
    const CheckReport report = check_against(scene, scene);
    EXPECT_TRUE(report.passed()) << "camera at y = " << y << "\n" << report.to_text();
    EXPECT_GT(report.both_hit, 96 * 54 / 2);
  }
}

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
  const Scene swapped =
      small_scene("torus.yaml", {{"render.normal_epsilon", "0.05"}, {"render.normal_method", "tetrahedral"}});
  EXPECT_TRUE(check_against(scene, scene).passed());
  const CheckReport report = check_against(scene, swapped);
  EXPECT_FALSE(report.passed()) << report.to_text();
}

// Misses are compared too: a background 3 steps of 8 bits off, and a glow of misses 5 % weaker,
// each fail the check on the miss criterion alone.
TEST(CheckTeeth, FailsWhenTheColorOfMissesDiffers) {
  const Scene scene = small_scene("torus.yaml");
  const CheckReport background =
      check_against(scene, small_scene("torus.yaml", {{"shading.background", "[0.012, 0, 0]"}}));
  EXPECT_FALSE(background.passed()) << background.to_text();
  ASSERT_EQ(background.failures.size(), 1u) << background.to_text();
  EXPECT_NE(background.failures[0].find("color error of misses"), std::string::npos) << background.to_text();

  const Scene bulb = small_scene("mandelbulb.yaml");
  const CheckReport glow =
      check_against(bulb, small_scene("mandelbulb.yaml", {{"shading.glow.color", "[0.3325, 0.285, 0.855]"}}));
  EXPECT_FALSE(glow.passed()) << glow.to_text();
  ASSERT_EQ(glow.failures.size(), 1u) << glow.to_text();
  EXPECT_NE(glow.failures[0].find("color error of misses"), std::string::npos) << glow.to_text();
  EXPECT_GT(glow.color_compared, glow.both_hit) << "misses must be among the pixels compared";
}

// A material slightly off changes only the shading: the geometry is the same, and the end-to-end
// color criterion, whose tolerance must cover the normals' differences, lets it through; the
// reference's color of the device's own hits does not. Smith's k doubled on pbr_sphere and a node's
// reflectivity ignored on lava_lamp (kernel mutants) were caught only this way.
TEST(CheckTeeth, FailsWhenOnlyTheShadingDiffers) {
  const Scene lamp = small_scene("lava_lamp.yaml");
  const CheckReport lamp_report =
      check_against(lamp, small_scene("lava_lamp.yaml", {{"sdf.union.1.plane.reflectivity", "0.36"}}));
  ASSERT_EQ(lamp_report.failures.size(), 1u) << lamp_report.to_text();
  EXPECT_NE(lamp_report.failures[0].find("shading error"), std::string::npos) << lamp_report.to_text();

  const Scene sphere = small_scene("pbr_sphere.yaml");
  const CheckReport sphere_report =
      check_against(sphere, small_scene("pbr_sphere.yaml", {{"sdf.sphere.roughness", "0.33"}}));
  ASSERT_EQ(sphere_report.failures.size(), 1u) << sphere_report.to_text();
  EXPECT_NE(sphere_report.failures[0].find("shading error"), std::string::npos) << sphere_report.to_text();
}

// The shading is compared on the same hits, not on the reference's: with epsilon below float's
// resolution at the spheres (2^-23 t ~ 5e-7 at t ~ 4) the float march stops up to 70 epsilons
// (within its depth tolerance) from where the double one does, and with a normal step of 3e-5
// the normals there differ enough to move the Blinn-Phong colors by more than half a step of 8
// bits at p99; shaded from the same depth and normal, the colors agree to float rounding.
TEST(CheckShading, ComparesTheSameHitsNotTheReferences) {
  const Scene scene =
      small_scene("two_spheres.yaml",
                  {{"render.epsilon", "1e-7"}, {"render.max_steps", "1000"}, {"render.normal_epsilon", "3e-5"}});
  const CheckReport report = check_against(scene, scene);
  EXPECT_TRUE(report.passed()) << report.to_text();
  EXPECT_GT(report.color_p99_abs, 0.5 / 255.0) << report.to_text();
  EXPECT_LT(report.shading_p99_abs, 0.05 / 255.0) << report.to_text();
}

TEST(CheckCli, ReportsAndExitsZeroWhenWithinTolerance) {
  const auto result =
      testing::run_clmarch({"check", source_path("scenes/torus.yaml").string(), "--size", "64x36", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err << result.out;
  const nlohmann::json report = nlohmann::json::parse(result.out);
  EXPECT_TRUE(report["passed"].get<bool>());
  for (const char* key : {"mask_mismatch", "depth_abs", "depth_rel", "depth_in_epsilons", "steps_diff",
                          "normal_angle_deg_p99", "color", "shading"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_GT(report["shading"]["compared"].get<int>(), 0) << "the device's hits are shaded by the reference too";
  // At least half a step of 8 bits (more where colors exceed 1), and above the figure it passed.
  EXPECT_GE(report["tolerances"]["shading_p99_abs"].get<double>(), 0.5 / 255.0);
  EXPECT_LE(report["shading"]["p99_abs"].get<double>(), report["tolerances"]["shading_p99_abs"].get<double>());
}

// A check that fails, end to end: exit code 1, the report says why, and --out-dir receives both
// renders and their difference. The scene fails for a documented reason (docs/scene-format.md,
// mandelbulb): at power 2 with 64 iterations the float orbit near the set drifts from the double
// one, so the kernel's normals are several times the tolerance away from the reference's.
TEST(CheckCli, AFailingCheckExitsOneAndWritesBothRendersAndTheirDifference) {
  TempDir dir;
  const std::filesystem::path scene = dir / "chaotic_bulb.yaml";
  std::ofstream(scene) << "camera: {position: [0, 0, 3], look_at: [0, 0, 0]}\n"
                          "render: {width: 48, height: 32}\n"
                          "sdf: {mandelbulb: {power: 2, iterations: 64, bailout: 2}}\n";
  const auto result = testing::run_clmarch({"check", scene.string(), "--out-dir", dir.path().string()});
  ASSERT_EQ(result.exit_code, 1) << result.err << result.out;
  EXPECT_NE(result.out.find("check FAILED:\n  normal angle error p99 is"), std::string::npos) << result.out;
  EXPECT_EQ(dir.files(),
            (std::vector<std::string>{"chaotic_bulb.yaml", "difference.exr", "opencl.png", "reference.png"}));
  const testing::Image opencl = testing::read_image(dir / "opencl.png");
  const testing::Image reference = testing::read_image(dir / "reference.png");
  const testing::Image difference = testing::read_image(dir / "difference.exr");
  for (const testing::Image* image : {&opencl, &reference, &difference}) {
    EXPECT_EQ(image->width, 48);
    EXPECT_EQ(image->height, 32);
  }
  ASSERT_EQ(difference.channels, 22)
      << "the --buffers channels but P: R, G, B, depth, steps, N.x, N.y, N.z, A, Z, samples, id, status, layers";
  // The difference holds |opencl - reference| per channel: here the normals (N.x, N.y, N.z).
  std::vector<int> normal_channels;
  {
    auto in = OIIO::ImageInput::open((dir / "difference.exr").string());
    ASSERT_TRUE(in);
    for (const char* name : {"N.x", "N.y", "N.z"}) normal_channels.push_back(in->spec().channelindex(name));
  }
  float largest_normal_difference = 0.0f;
  for (int j = 0; j < 32; ++j) {
    for (int i = 0; i < 48; ++i) {
      for (int c : normal_channels) {
        ASSERT_GE(c, 0);
        largest_normal_difference = std::max(largest_normal_difference, difference.at(i, j, c));
      }
    }
  }
  EXPECT_GT(largest_normal_difference, 0.1f) << "the failure the report names must show in the difference";

  // Passing, nothing is written.
  TempDir quiet;
  const auto pass = testing::run_clmarch(
      {"check", source_path("scenes/torus.yaml").string(), "--size", "48x32", "--out-dir", quiet.path().string()});
  ASSERT_EQ(pass.exit_code, 0) << pass.err << pass.out;
  EXPECT_TRUE(quiet.files().empty());
}

// Each criterion's threshold, pinned: the reference render against a copy of itself perturbed to
// a multiple of the criterion's documented per-pixel tolerance (docs/accuracy.md) fails just past
// 1 and passes within it. Without this, a threshold loosened threefold went unnoticed (mutation
// testing): the teeth tests above perturb far past every threshold.
class CheckThresholds : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = small_scene("torus.yaml");
    ASSERT_EQ(scene_.render.hit_threshold, HitThreshold::Fixed) << "the tolerances below assume a fixed epsilon";
    reference_ = render_reference(scene_);
    basis_ = camera_basis(scene_.camera, reference_.width, reference_.height);
  }
  bool hit(int i, int j) const { return std::isfinite(reference_.at(Channel::Depth, i, j)); }
  /// Hit or miss like all 8 neighbours: the pixels every criterion but the silhouette's compares.
  bool interior(int i, int j) const {
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const int ni = i + di, nj = j + dj;
        if (ni < 0 || nj < 0 || ni >= reference_.width || nj >= reference_.height || hit(ni, nj) != hit(i, j))
          return false;
      }
    }
    return true;
  }
  /// Float rounding of a ray's depth t: 16 unit roundoffs of the coordinates' size.
  double rounding(double t) const { return 16.0 * 0x1p-24 * (glm::length(basis_.origin) + t); }
  /// The reference with change applied to its interior pixels.
  template <typename Change>
  FrameBuffers changed_copy(Change change) const {
    FrameBuffers copy = reference_;
    for (int j = 0; j < copy.height; ++j) {
      for (int i = 0; i < copy.width; ++i) {
        if (interior(i, j)) change(copy, i, j);
      }
    }
    return copy;
  }
  template <typename Change>
  CheckReport perturbed(Change change) const {
    return cross_check(scene_, changed_copy(change), reference_);
  }
  /// The same, checked with the shading of the copy's hits as `clmarch check` does.
  template <typename Change>
  CheckReport perturbed_and_reshaded(Change change) const {
    const FrameBuffers copy = changed_copy(change);
    return cross_check(scene_, copy, reference_, reshade_hits(scene_, copy));
  }
  static bool failed_on(const CheckReport& report, const std::string& criterion) {
    return std::any_of(report.failures.begin(), report.failures.end(),
                       [&](const std::string& f) { return f.find(criterion) != std::string::npos; });
  }
  Scene scene_;
  FrameBuffers reference_;
  CameraBasis basis_;
};

TEST_F(CheckThresholds, DepthAtItsTolerancePerPixel) {
  // epsilon / max(|cos|, 0.1) + rounding, the march stopping short of the surface.
  const auto shift_by = [&](double multiple) {
    return perturbed([&](FrameBuffers& b, int i, int j) {
      if (!hit(i, j)) return;
      const double t = reference_.at(Channel::Depth, i, j);
      const glm::dvec3 n(reference_.at(Channel::NX, i, j), reference_.at(Channel::NY, i, j),
                         reference_.at(Channel::NZ, i, j));
      const double cosine = std::max(std::abs(glm::dot(pixel_ray_direction(basis_, i, j), n)), 0.1);
      b.at(Channel::Depth, i, j) = static_cast<float>(t - multiple * (scene_.render.epsilon / cosine + rounding(t)));
    });
  };
  EXPECT_FALSE(failed_on(shift_by(0.7), "depth error")) << shift_by(0.7).to_text();
  EXPECT_TRUE(failed_on(shift_by(1.5), "depth error")) << shift_by(1.5).to_text();
}

TEST_F(CheckThresholds, NormalsAtTheirToleranceForEqualDepths) {
  // sqrt(3) (dt + rounding) / h, here with dt = 0: the normals turned about an axis across them.
  const auto turn_by = [&](double multiple) {
    return perturbed([&](FrameBuffers& b, int i, int j) {
      if (!hit(i, j)) return;
      const double t = reference_.at(Channel::Depth, i, j);
      const double angle = multiple * std::sqrt(3.0) * rounding(t) / scene_.render.normal_epsilon;
      const glm::dvec3 n(reference_.at(Channel::NX, i, j), reference_.at(Channel::NY, i, j),
                         reference_.at(Channel::NZ, i, j));
      const glm::dvec3 across =
          glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
      const glm::dvec3 turned = std::cos(angle) * n + std::sin(angle) * across;
      b.at(Channel::NX, i, j) = static_cast<float>(turned.x);
      b.at(Channel::NY, i, j) = static_cast<float>(turned.y);
      b.at(Channel::NZ, i, j) = static_cast<float>(turned.z);
    });
  };
  EXPECT_FALSE(failed_on(turn_by(0.5), "normal angle")) << turn_by(0.5).to_text();
  EXPECT_TRUE(failed_on(turn_by(1.5), "normal angle")) << turn_by(1.5).to_text();
}

TEST_F(CheckThresholds, ColorOfMissesAtHalfAnEightBitStep) {
  // The torus has no glow: a miss's color is the sky's, to half a step of 8 bits.
  const auto brighten_by = [&](double multiple) {
    return perturbed([&](FrameBuffers& b, int i, int j) {
      if (!hit(i, j)) b.at(Channel::R, i, j) += static_cast<float>(multiple * 0.5 / 255.0);
    });
  };
  EXPECT_FALSE(failed_on(brighten_by(0.5), "color error of misses")) << brighten_by(0.5).to_text();
  EXPECT_TRUE(failed_on(brighten_by(1.5), "color error of misses")) << brighten_by(1.5).to_text();
}

TEST_F(CheckThresholds, ColorOfHitsAtTheShadingSlopeTimesTheNormalTolerance) {
  // Half a step of 8 bits plus the color's largest change per radian of normal (the lights'
  // radiance times the diffuse and specular slopes) times the normal tolerance, here dt = 0.
  double radiance = 0.0;
  for (const Light& light : scene_.lights)
    radiance += light.intensity * std::max({light.color.r, light.color.g, light.color.b});
  const Shading& shading = scene_.shading;
  ASSERT_GT(radiance, 0.0);
  const double specular = shading.model == ShadingModel::Lambert ? 0.0 : shading.specular * shading.shininess;
  const double per_radian = radiance * (shading.diffuse + specular);
  const auto brighten_by = [&](double multiple) {
    return perturbed([&](FrameBuffers& b, int i, int j) {
      if (!hit(i, j)) return;
      const double normal_tolerance =
          std::sqrt(3.0) * rounding(reference_.at(Channel::Depth, i, j)) / scene_.render.normal_epsilon;
      b.at(Channel::G, i, j) += static_cast<float>(multiple * (per_radian * normal_tolerance + 0.5 / 255.0));
    });
  };
  EXPECT_FALSE(failed_on(brighten_by(0.7), "color error p99")) << brighten_by(0.7).to_text();
  EXPECT_TRUE(failed_on(brighten_by(1.5), "color error p99")) << brighten_by(1.5).to_text();
}

TEST_F(CheckThresholds, ShadingAtHalfAnEightBitStep) {
  // The same hits shaded by both sides: only float arithmetic separates them, far below half a
  // step of 8 bits, the tolerance.
  const auto brighten_by = [&](double multiple) {
    return perturbed_and_reshaded([&](FrameBuffers& b, int i, int j) {
      if (hit(i, j)) b.at(Channel::G, i, j) += static_cast<float>(multiple * 0.5 / 255.0);
    });
  };
  EXPECT_FALSE(failed_on(brighten_by(0.9), "shading error")) << brighten_by(0.9).to_text();
  EXPECT_TRUE(failed_on(brighten_by(1.1), "shading error")) << brighten_by(1.1).to_text();
  // Every hit shaded by one ray counts once, with its layers or without them (a render of the
  // shaded program, which writes none).
  int single_ray_hits = 0;
  for (int j = 0; j < reference_.height; ++j) {
    for (int i = 0; i < reference_.width; ++i) single_ray_hits += hit(i, j);
  }
  FrameBuffers without_layers = reference_;
  without_layers.has_layers = false;
  EXPECT_EQ(cross_check(scene_, reference_, reference_, reshade_hits(scene_, reference_)).shading_compared,
            single_ray_hits);
  EXPECT_EQ(cross_check(scene_, without_layers, reference_, reshade_hits(scene_, without_layers)).shading_compared,
            single_ray_hits);
  // Each layer is held to the same tolerance as the color.
  for (Channel layer : {Channel::AoB, Channel::DiffuseR, Channel::SpecularG}) {
    const auto layer_off_by = [&](double multiple) {
      return perturbed_and_reshaded([&](FrameBuffers& b, int i, int j) {
        if (hit(i, j)) b.at(layer, i, j) += static_cast<float>(multiple * 0.5 / 255.0);
      });
    };
    EXPECT_FALSE(failed_on(layer_off_by(0.9), "shading error")) << kChannelNames[static_cast<int>(layer)];
    EXPECT_TRUE(failed_on(layer_off_by(1.1), "shading error")) << kChannelNames[static_cast<int>(layer)];
  }
}

// A NaN or an infinity where the contract has a number fails the check, whichever side holds it:
// a NaN would drop out of every max and sort, and compare as agreement.
TEST_F(CheckThresholds, ANanOrAnInfinityFails) {
  int hit_i = -1, hit_j = -1;
  for (int j = 0; j < reference_.height && hit_i < 0; ++j) {
    for (int i = 0; i < reference_.width; ++i) {
      if (interior(i, j) && hit(i, j)) {
        hit_i = i;
        hit_j = j;
        break;
      }
    }
  }
  ASSERT_GE(hit_i, 0);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  // A +inf depth is a miss, not a bad value.
  const std::vector<std::pair<Channel, float>> bad_values = {
      {Channel::R, nan}, {Channel::R, inf}, {Channel::NX, nan}, {Channel::NX, inf}, {Channel::Depth, nan}};
  for (const auto& [channel, bad] : bad_values) {
    SCOPED_TRACE(fmt::format("{} = {}", kChannelNames[static_cast<int>(channel)], bad));
    FrameBuffers copy = reference_;
    copy.at(channel, hit_i, hit_j) = bad;
    const CheckReport on_opencl = cross_check(scene_, copy, reference_);
    EXPECT_TRUE(failed_on(on_opencl, "1 OpenCL and 0 reference pixels hold a NaN or an infinity"))
        << on_opencl.to_text();
    const CheckReport on_reference = cross_check(scene_, reference_, copy);
    EXPECT_TRUE(failed_on(on_reference, "0 OpenCL and 1 reference pixels hold a NaN or an infinity"))
        << on_reference.to_text();
    if (channel == Channel::R) {
      EXPECT_TRUE(std::isinf(on_opencl.color_max_abs)) << "a NaN must not drop out of the max";
    }
  }
}

TEST_F(CheckThresholds, StepsAtOneOnAverage) {
  const auto add_steps = [&](int every, float steps) {
    int n = 0;
    return perturbed([&](FrameBuffers& b, int i, int j) {
      if (n++ % every == 0) b.at(Channel::Steps, i, j) += steps;
    });
  };
  EXPECT_FALSE(failed_on(add_steps(2, 1.0f), "steps differ")) << add_steps(2, 1.0f).to_text();
  EXPECT_TRUE(failed_on(add_steps(1, 2.0f), "steps differ")) << add_steps(1, 2.0f).to_text();
}

// A union evaluated from an operand grid is a lower bound of itself outside the grid, so the
// kernel's rays take more steps there by design: only steps short of the reference's count.
TEST(CheckSteps, OperandGridScenesCountOnlyStepsShortOfTheReference) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 1, 4], look_at: [0, 0, 0]}\nrender: {width: 32, height: 18, pruning: grid}\n"
      "sdf: {union: [{sphere: {radius: 0.8}}, {sphere: {center: [1, 0, 0], radius: 0.5}}]}\n");
  const FrameBuffers reference = render_reference(scene);
  const auto with_steps_added = [&](float steps) {
    FrameBuffers copy = reference;
    for (int j = 0; j < copy.height; ++j) {
      for (int i = 0; i < copy.width; ++i) copy.at(Channel::Steps, i, j) += steps;
    }
    return cross_check(scene, copy, reference);
  };
  const CheckReport more = with_steps_added(3.0f), fewer = with_steps_added(-3.0f);
  EXPECT_TRUE(more.steps_one_sided);
  EXPECT_EQ(more.steps_diff_mean, 0.0) << more.to_text();
  EXPECT_EQ(fewer.steps_diff_mean, 3.0) << fewer.to_text();
  EXPECT_FALSE(fewer.passed()) << fewer.to_text();
}

TEST_F(CheckThresholds, InteriorHitMaskFlipsAtOneInAThousand) {
  // A pixel flips as an interior one only with its 8 neighbours flipped too: blocks of 3 x 3 hits
  // made misses, one interior flip each (and 8 at its silhouette).
  const int allowed = static_cast<int>(std::ceil(0.001 * reference_.width * reference_.height));
  const auto flip_blocks = [&](int blocks) {
    FrameBuffers copy = reference_;
    int made = 0;
    for (int j = 2; j + 2 < copy.height && made < blocks; ++j) {
      for (int i = 2; i + 2 < copy.width && made < blocks; ++i) {
        // A ring of hits, in both renders, around each block keeps its flips its own.
        bool all_hits = true;
        for (int dj = -2; dj <= 2; ++dj) {
          for (int di = -2; di <= 2; ++di) {
            all_hits = all_hits && hit(i + di, j + dj) && std::isfinite(copy.at(Channel::Depth, i + di, j + dj));
          }
        }
        if (!all_hits) continue;
        for (int dj = -1; dj <= 1; ++dj) {
          for (int di = -1; di <= 1; ++di)
            copy.at(Channel::Depth, i + di, j + dj) = std::numeric_limits<float>::infinity();
        }
        ++made;
      }
    }
    EXPECT_EQ(made, blocks) << "the torus has room for the blocks";
    return cross_check(scene_, copy, reference_);
  };
  const CheckReport within = flip_blocks(allowed);
  EXPECT_EQ(within.mask_mismatch_interior, allowed);
  EXPECT_FALSE(failed_on(within, "interior pixels")) << within.to_text();
  const CheckReport past = flip_blocks(allowed + 1);
  EXPECT_TRUE(failed_on(past, "interior pixels")) << past.to_text();
}

TEST_F(CheckThresholds, IdMismatchesAwayFromIdEdgesAtOneInAThousand) {
  // Blocks of 3 x 3 hits given another primitive's number: the centre of each is an interior
  // mismatch, its ring edge ones (8 a block, within a tenth of the edge pixels only for few blocks).
  const int allowed = static_cast<int>(std::ceil(0.001 * reference_.width * reference_.height));
  const auto renumber_blocks = [&](int blocks) {
    FrameBuffers copy = reference_;
    int made = 0;
    // A block every 4 pixels: the column and row between blocks keep the reference's number.
    for (int j = 2; j + 2 < copy.height && made < blocks; j += 4) {
      for (int i = 2; i + 2 < copy.width && made < blocks; i += 4) {
        bool all_hits = true;
        for (int dj = -2; dj <= 2; ++dj) {
          for (int di = -2; di <= 2; ++di) all_hits = all_hits && hit(i + di, j + dj);
        }
        if (!all_hits) continue;
        for (int dj = -1; dj <= 1; ++dj) {
          for (int di = -1; di <= 1; ++di) copy.at(Channel::Id, i + di, j + dj) = 7.0f;
        }
        ++made;
      }
    }
    EXPECT_EQ(made, blocks) << "the torus has room for the blocks";
    return cross_check(scene_, copy, reference_, reshade_hits(scene_, copy));
  };
  const CheckReport within = renumber_blocks(allowed);
  EXPECT_EQ(within.id_mismatch_interior, allowed);
  EXPECT_EQ(within.id_mismatch_edge, 8 * allowed);
  EXPECT_FALSE(failed_on(within, "away from id edges")) << within.to_text();
  const CheckReport past = renumber_blocks(allowed + 1);
  EXPECT_TRUE(failed_on(past, "away from id edges")) << past.to_text();
  // Renumbered everywhere, the edges are the hits next to misses: far past a tenth of them.
  const CheckReport everywhere = perturbed_and_reshaded([](FrameBuffers& b, int i, int j) {
    if (std::isfinite(b.at(Channel::Depth, i, j))) b.at(Channel::Id, i, j) = 3.0f;
  });
  EXPECT_TRUE(failed_on(everywhere, "away from id edges")) << everywhere.to_text();
  EXPECT_EQ(reference_.at(Channel::Id, reference_.width / 2, reference_.height / 2) >= 0.0f,
            hit(reference_.width / 2, reference_.height / 2));
}

}  // namespace
}  // namespace clmarch

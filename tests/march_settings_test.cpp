// The march settings of issue 6: over-relaxed sphere tracing (Keinert et al. 2014) and the
// pixel-cone hit threshold. Each does what docs/scene-format.md claims, the same way in the
// OpenCL kernels and the CPU reference, and bad values are one-line errors.
#include "analytic_intersections.hpp"
#include "check/cross_check.hpp"
#include "common/errors.hpp"
#include "reference/reference_march.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"
#include "support/tolerances.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace clmarch {
namespace {

using testing::kFloatRelative;
using testing::kGrazingCosine;
using testing::scene_from_yaml;
using testing::total_steps;

Scene load_shipped_scene(const std::string& name, int width, int height) {
  Scene scene = load_scene_file(testing::source_path("scenes/" + name).string());
  scene.render.width = width;
  scene.render.height = height;
  return scene;
}

FrameBuffers render_depth(const Scene& scene, int lanes = 16) {
  OpenClOptions options;
  options.lanes = lanes;
  options.purpose = KernelPurpose::Normals;
  return render_opencl(scene, options).buffers;
}

TEST(MarchSettings, DefaultsAreAutomaticOverRelaxationWithTheFixedEpsilon) {
  const Scene scene = scene_from_yaml("sdf: {sphere: {}}\n");
  EXPECT_FALSE(scene.render.over_relaxation.has_value());
  EXPECT_EQ(camera_over_relaxation(scene), kAutoOverRelaxation);
  EXPECT_EQ(camera_over_relaxation(scene_from_yaml("sdf: {sphere: {}}\nrender: {over_relaxation: auto}\n")), 1.2);
  // Plain sphere tracing where the steps are the picture (step-count occlusion) and in the cells
  // tiling; a number given always wins.
  EXPECT_EQ(camera_over_relaxation(scene_from_yaml("sdf: {sphere: {}}\nshading: {step_ao: 3000}\n")), 1.0);
  EXPECT_EQ(camera_over_relaxation(scene_from_yaml("sdf: {sphere: {}}\ntiling: {cell: [4, 4, 4]}\n")), 1.0);
  EXPECT_EQ(camera_over_relaxation(scene_from_yaml("sdf: {sphere: {}}\ntiling: {cell: [4, 4, 4], method: mod}\n")),
            1.2);
  EXPECT_EQ(camera_over_relaxation(scene_from_yaml("sdf: {sphere: {}}\nrender: {over_relaxation: 1}\n")), 1.0);
  EXPECT_EQ(camera_over_relaxation(
                scene_from_yaml("sdf: {sphere: {}}\nrender: {over_relaxation: 1.5}\nshading: {step_ao: 3000}\n")),
            1.5);
  EXPECT_EQ(scene.render.hit_threshold, HitThreshold::Fixed);
  EXPECT_EQ(scene.render.cone_factor, 1.0);
  EXPECT_EQ(hit_cone_slope(scene.render, scene.camera), 0.0);
  const Scene cone = scene_from_yaml(
      "sdf: {sphere: {}}\ncamera: {fov: 90}\nrender: {height: 100, hit_threshold: pixel_cone, cone_factor: 0.5, "
      "over_relaxation: 1.25}\n");
  EXPECT_EQ(cone.render.over_relaxation, 1.25);
  // 0.5 * 2 tan(45 degrees) / 100
  EXPECT_NEAR(hit_cone_slope(cone.render, cone.camera), 0.01, 1e-15);
}

// A plane seen head-on: the relaxed step 1.5 * 5 lands 2.5 inside the solid, the spheres of radius
// 5 and -2.5 do not overlap, so the sample is discarded (no hit inside) and the march goes back to
// t = 5, where plain sphere tracing would be: 3 evaluations instead of 2, and the exact depth.
constexpr const char* kHeadOnPlane =
    "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\n"
    "render: {width: 1, height: 1}\n"
    "sdf: {plane: {normal: [0, 0, 1], offset: 0}}\n";

TEST(OverRelaxation, StepIntoTheSolidFallsBackInTheReference) {
  Scene scene = scene_from_yaml(kHeadOnPlane);
  for (const auto& [omega, steps] : {std::pair{1.0, 2}, std::pair{1.5, 3}}) {
    scene.render.over_relaxation = omega;
    const MarchEnd end =
        reference_march(scene, scene.camera.position, {0.0, 0.0, -1.0}, 0.0, 100.0, camera_march_limits(scene));
    EXPECT_TRUE(end.hit) << "omega " << omega;
    EXPECT_EQ(end.depth, 5.0) << "omega " << omega;
    EXPECT_EQ(end.steps, steps) << "omega " << omega;
  }
}

TEST(OverRelaxation, StepIntoTheSolidFallsBackInTheKernel) {
  Scene scene = scene_from_yaml(kHeadOnPlane);
  for (int lanes : {1, 16}) {
    for (const auto& [omega, steps] : {std::pair{1.0, 2}, std::pair{1.5, 3}}) {
      scene.render.over_relaxation = omega;
      const FrameBuffers b = render_depth(scene, lanes);
      EXPECT_EQ(b.at(Channel::Depth, 0, 0), 5.0f) << "omega " << omega << ", lanes " << lanes;
      EXPECT_EQ(b.at(Channel::Steps, 0, 0), steps) << "omega " << omega << ", lanes " << lanes;
    }
  }
}

// The relaxed march never reports a point past the surface: against the closed-form torus, every
// relaxed reference hit lies in front of the exact one by at most epsilon / cos.
TEST(OverRelaxation, ReferenceHitsNeverPassTheSurface) {
  Scene scene = load_shipped_scene("torus.yaml", 64, 36);
  scene.render.over_relaxation = 1.6;
  const Torus& torus = std::get<Torus>(scene.sdf.params);
  ASSERT_TRUE(scene.sdf.transform.is_identity());
  const CameraBasis basis = camera_basis(scene.camera, scene.render.width, scene.render.height);
  int hits = 0, near_misses = 0;
  for (int j = 0; j < scene.render.height; ++j) {
    for (int i = 0; i < scene.render.width; ++i) {
      const glm::dvec3 dir = pixel_ray_direction(basis, i, j);
      const MarchEnd end =
          reference_march(scene, basis.origin, dir, 0.0, scene.render.max_distance, camera_march_limits(scene));
      if (!end.hit) continue;
      ++hits;
      const std::optional<double> exact = intersect_torus(basis.origin, dir, torus);
      if (!exact) {
        ++near_misses;  // a silhouette ray passing within epsilon of the surface
        continue;
      }
      EXPECT_LE(end.depth, *exact + 1e-12) << i << "," << j;
      // The exact hit's normal: away from the nearest point of the torus' core circle.
      const glm::dvec3 q = basis.origin + *exact * dir - torus.center;
      const glm::dvec3 core = torus.major_radius * glm::normalize(glm::dvec3(q.x, 0.0, q.z));
      const double cosine = std::abs(glm::dot(dir, glm::normalize(q - core)));
      if (cosine < kGrazingCosine) continue;
      EXPECT_GE(end.depth, *exact - scene.render.epsilon / cosine - 1e-12) << i << "," << j;
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_LE(near_misses, 2);
}

// On the torus, omega = 1.2 saves steps; hit masks change at most on silhouettes and depths stay
// within the check's per-pixel tolerance of plain sphere tracing.
TEST(OverRelaxation, FewerStepsOnTheTorusSameImage) {
  const Scene plain = load_shipped_scene("torus.yaml", 160, 90);
  Scene relaxed = plain;
  relaxed.render.over_relaxation = 1.2;
  const FrameBuffers a = render_depth(plain);
  const FrameBuffers b = render_depth(relaxed);
  EXPECT_LT(total_steps(b), 0.97 * total_steps(a)) << "plain " << total_steps(a) << ", relaxed " << total_steps(b);
  const CheckReport report = cross_check(plain, b, a);
  EXPECT_EQ(report.mask_mismatch_interior, 0);
  EXPECT_LE(report.mask_mismatch_silhouette, report.tolerances.mask_mismatch_silhouette);
  EXPECT_LE(report.depth_in_tolerances.p99, 1.0);
  EXPECT_GT(report.both_hit, 1000);
}

// A floor receding to the horizon: with the pixel cone every ray follows the same t sequence as with
// the fixed epsilon (both from the camera: no coarse pass) and stops no later, so per pixel it takes no more steps and
// hits wherever the fixed march hits, at most threshold / cos in front of the exact plane; near the camera, where the
// cone is narrower than epsilon (0.02 here, so that such pixels exist), nothing changes; far away
// most steps are saved.
TEST(PixelCone, FewerStepsAtDistanceOnAFloor) {
  const Scene fixed = scene_from_yaml(
      "camera: {position: [0, 1, 0], look_at: [0, -2, -10], fov: 45}\n"
      "render: {width: 160, height: 90, max_distance: 100, epsilon: 0.02, coarse_pass: none}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0}}\n");
  Scene cone = fixed;
  cone.render.hit_threshold = HitThreshold::PixelCone;
  const double slope = hit_cone_slope(cone.render, cone.camera);
  const double near_limit = cone.render.epsilon / slope;  // below this depth the cone is narrower than epsilon
  const FrameBuffers a = render_depth(fixed);
  const FrameBuffers b = render_depth(cone);
  const CameraBasis basis = camera_basis(fixed.camera, fixed.render.width, fixed.render.height);
  double far_fixed = 0.0, far_cone = 0.0;
  int near_pixels = 0;
  for (int j = 0; j < fixed.render.height; ++j) {
    for (int i = 0; i < fixed.render.width; ++i) {
      const float steps_fixed = a.at(Channel::Steps, i, j), steps_cone = b.at(Channel::Steps, i, j);
      const float t_fixed = a.at(Channel::Depth, i, j), t_cone = b.at(Channel::Depth, i, j);
      ASSERT_LE(steps_cone, steps_fixed) << i << "," << j;
      if (std::isfinite(t_fixed)) {
        ASSERT_TRUE(std::isfinite(t_cone)) << i << "," << j;
      }
      if (!std::isfinite(t_cone)) continue;
      const glm::dvec3 dir = pixel_ray_direction(basis, i, j);
      const double exact = -basis.origin.y / dir.y;
      const double cosine = std::abs(dir.y);
      if (cosine >= kGrazingCosine) {
        const double threshold = std::max(cone.render.epsilon, slope * exact);
        const double rounding = kFloatRelative * (1.0 + exact);
        EXPECT_LE(t_cone, exact + rounding) << i << "," << j;
        EXPECT_GE(t_cone, exact - threshold / cosine - rounding) << i << "," << j;
      }
      if (t_fixed < near_limit) {
        ++near_pixels;
        EXPECT_EQ(steps_cone, steps_fixed) << i << "," << j;
        EXPECT_EQ(t_cone, t_fixed) << i << "," << j;
      } else if (std::isfinite(t_fixed) && t_fixed > 10.0) {
        far_fixed += steps_fixed;
        far_cone += steps_cone;
      }
    }
  }
  EXPECT_GT(near_pixels, 100);
  ASSERT_GT(far_fixed, 0.0);
  EXPECT_LT(far_cone, 0.5 * far_fixed) << "steps beyond depth 10: fixed " << far_fixed << ", cone " << far_cone;
}

// With either setting on, the kernel and the reference still agree within the check's tolerances:
// an exact field, the cells tiling (relaxed steps end at cell walls) and a bound (terrain).
TEST(MarchSettings, KernelAndReferenceAgreeWithTheSettingsOn) {
  for (const char* name : {"torus.yaml", "tiled_spheres.yaml", "terrain_fbm.yaml"}) {
    for (int setting = 0; setting < 3; ++setting) {
      Scene scene = load_shipped_scene(name, 80, 45);
      if (setting != 1) scene.render.over_relaxation = 1.5;
      if (setting != 0) scene.render.hit_threshold = HitThreshold::PixelCone;
      OpenClOptions options;
      options.purpose = KernelPurpose::Shaded;
      const FrameBuffers opencl = render_opencl(scene, options).buffers;
      const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
      EXPECT_TRUE(report.passed()) << name << ", setting " << setting << ":\n" << report.to_text();
    }
  }
}

// Bad values through the real executable: one line naming the file position or --set, exit 2.
TEST(MarchSettings, BadValuesAreOneLineErrors) {
  testing::TempDir dir;
  const std::string scene = (dir / "scene.yaml").string();
  std::ofstream(scene) << "sdf: {sphere: {}}\nrender: {width: 8, height: 8}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"render.over_relaxation=2", "render.over_relaxation must be in [1, 2) (got 2)"},
      {"render.over_relaxation=0.9", "render.over_relaxation must be in [1, 2) (got 0.9)"},
      {"render.over_relaxation=fast", "render.over_relaxation must be a number in [1, 2) or auto (got 'fast')"},
      {"render.over_relaxation=[1.2]", "render.over_relaxation must be a number (got a list)"},
      {"render.over_relaxation=2*t+3", "render.over_relaxation must be in [1, 2) (got 2*t+3 = 3 at t = 0)"},
      {"render.hit_threshold=cone", "fixed, pixel_cone"},
      {"render={hit_threshold: pixel_cone, cone_factor: 0}", "render.cone_factor must be > 0 (got 0)"},
      {"render.cone_factor=2", "render.cone_factor applies only with render.hit_threshold: pixel_cone"},
  };
  for (const auto& [set, message] : cases) {
    const testing::CommandResult r =
        testing::run_clmarch({"render", scene, "--set", set, "-o", (dir / "out.png").string()});
    EXPECT_EQ(r.exit_code, kExitBadInput) << set;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << set << ":\n" << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << set << ":\n" << r.err;
    EXPECT_NE(r.err.find("(--set)"), std::string::npos) << set << ":\n" << r.err;
  }
  std::ofstream(scene) << "sdf: {sphere: {}}\nrender: {over_relaxation: 3}\n";
  const testing::CommandResult r = testing::run_clmarch({"render", scene, "-o", (dir / "out.png").string()});
  EXPECT_NE(r.err.find("scene.yaml:2:27: render.over_relaxation must be in [1, 2) (got 3)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

}  // namespace
}  // namespace clmarch

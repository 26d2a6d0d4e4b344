// The status channel (issue 26): how each centre ray ended — a hit, a miss (it left the scene's
// bounding sphere or never met it), out of render.max_steps, or out of render.max_distance — alike
// on both backends, counted by --stats and drawn by the status view.
#include "analytic_intersections.hpp"
#include "frame/views.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <fstream>

namespace clmarch {
namespace {

constexpr int kStatusWidth = 32;
constexpr int kStatusHeight = 18;

/// A unit sphere 5 away, seen at 60 degrees: its silhouette covers the middle of the image.
Scene unit_sphere_scene(const std::string& render) {
  return testing::scene_from_yaml(
      fmt::format("camera: {{position: [0, 0, 5], look_at: [0, 0, 0], fov: 60}}\n"
                  "render: {{width: {}, height: {}, max_distance: 30, {}}}\n"
                  "sdf: {{sphere: {{radius: 1}}}}\n",
                  kStatusWidth, kStatusHeight, render));
}

RayStatus status_at(const FrameBuffers& b, int i, int j) { return static_cast<RayStatus>(b.at(Channel::Status, i, j)); }

/// Both backends' buffers of scene (the OpenCL --buffers program, which writes the status).
std::vector<std::pair<std::string, FrameBuffers>> both_backends(const Scene& scene) {
  OpenClOptions options;
  options.purpose = KernelPurpose::Buffers;
  return {{"opencl", render_opencl(scene, options).buffers}, {"reference", render_reference(scene)}};
}

/// For each pixel whose ray clearly hits or clearly misses the unit sphere (its closest approach
/// to the centre more than 0.05 from the radius), expects a hit where it hits and `missed` elsewhere.
void expect_sphere_statuses(const Scene& scene, RayStatus missed) {
  const CameraBasis basis = camera_basis(scene.camera, kStatusWidth, kStatusHeight);
  for (const auto& [backend, buffers] : both_backends(scene)) {
    SCOPED_TRACE(backend);
    ASSERT_TRUE(buffers.has_status);
    int hits = 0, misses = 0;
    for (int j = 0; j < kStatusHeight; ++j) {
      for (int i = 0; i < kStatusWidth; ++i) {
        const glm::dvec3 d = pixel_ray_direction(basis, i, j);
        const double closest = glm::length(glm::cross(-basis.origin, d));
        if (std::abs(closest - 1.0) < 0.05) continue;
        const bool hit = intersect_sphere(basis.origin, d, Sphere{glm::dvec3(0.0), 1.0}).has_value();
        EXPECT_EQ(status_at(buffers, i, j), hit ? RayStatus::Hit : missed) << i << ", " << j;
        hits += hit;
        misses += !hit;
      }
    }
    EXPECT_GT(hits, 20);
    EXPECT_GT(misses, 100);
  }
}

// Clipped to the scene's bounding sphere, a ray that misses the unit sphere leaves the bound: a miss.
TEST(RayStatus, RaysLeavingTheBoundsMiss) {
  expect_sphere_statuses(unit_sphere_scene("bounds: sphere"), RayStatus::Miss);
}

// Without the bound the same rays march on until max_distance: out of distance.
TEST(RayStatus, UnboundedRaysRunOutOfDistance) {
  expect_sphere_statuses(unit_sphere_scene("bounds: none"), RayStatus::OutOfDistance);
}

// A sphere 60 away with max_distance 30: the rays that meet its bounding sphere meet it past
// max_distance (out of distance, though they never march), the others miss it, and the shaded
// program that --stats gives a status plane says so as the --buffers program and the reference
// do. The kernel once started the missing rays at their closest approach to the bound, 60 away,
// and called them out of distance too.
TEST(RayStatus, ASceneBeyondMaxDistanceIsOutOfDistanceWhereItsRaysMeetIt) {
  const Scene scene =
      testing::scene_from_yaml(fmt::format("camera: {{position: [0, 0, 0], look_at: [0, 0, -60], fov: 4}}\n"
                                           "render: {{width: {}, height: {}, max_distance: 30}}\n"
                                           "sdf: {{sphere: {{center: [0, 0, -60], radius: 1}}}}\n",
                                           kStatusWidth, kStatusHeight));
  const CameraBasis basis = camera_basis(scene.camera, kStatusWidth, kStatusHeight);
  OpenClOptions shaded;
  shaded.ray_status = true;
  auto renders = both_backends(scene);
  renders.emplace_back("opencl shaded", render_opencl(scene, shaded).buffers);
  for (const auto& [backend, buffers] : renders) {
    SCOPED_TRACE(backend);
    int met = 0, missed = 0;
    for (int j = 0; j < kStatusHeight; ++j) {
      for (int i = 0; i < kStatusWidth; ++i) {
        const glm::dvec3 d = pixel_ray_direction(basis, i, j);
        const double closest = glm::length(glm::cross(glm::dvec3(0, 0, -60) - basis.origin, d));
        if (std::abs(closest - 1.0) < 0.1) continue;
        EXPECT_EQ(status_at(buffers, i, j), closest < 1.0 ? RayStatus::OutOfDistance : RayStatus::Miss)
            << i << ", " << j;
        met += closest < 1.0;
        missed += closest >= 1.0;
      }
    }
    EXPECT_GT(met, 20);
    EXPECT_GT(missed, 100);
  }
}

// One step from 5 away reaches neither the sphere (4 away) nor max_distance: every ray is out of
// steps, which shades as a miss (depth +inf). Fails when the kernel forgets which lanes its step
// budget stopped (every ray then reads as a miss).
TEST(RayStatus, OneStepLeavesEveryRayOutOfSteps) {
  const Scene scene = unit_sphere_scene("bounds: none, max_steps: 1");
  for (const auto& [backend, buffers] : both_backends(scene)) {
    SCOPED_TRACE(backend);
    EXPECT_EQ(buffers.rays_with_status(RayStatus::OutOfSteps),
              static_cast<std::uint64_t>(kStatusWidth * kStatusHeight));
    EXPECT_TRUE(std::isinf(buffers.at(Channel::Depth, kStatusWidth / 2, kStatusHeight / 2)));
  }
}

// A floor seen towards the horizon with a budget of 12 steps: the four endings side by side. Both
// backends take the same decision at every pixel, --stats counts the rays out of steps (also for
// the shaded program, which writes the status only when asked), and the status view draws each
// ending in its documented color.
TEST(RayStatus, StatsCountThemAndTheStatusViewShowsThem) {
  testing::TempDir dir;
  const std::string yaml =
      "camera: {position: [0, 1, 6], look_at: [0, 0, 0], fov: 60}\n"
      "render: {width: 64, height: 36, max_steps: 12, max_distance: 30}\n"
      "sdf: {union: [{sphere: {radius: 1}}, {plane: {normal: [0, 1, 0], offset: 1}}]}\n";
  std::ofstream(dir / "scene.yaml") << yaml;
  const Scene scene = testing::scene_from_yaml(yaml);
  const auto buffers = both_backends(scene);
  const FrameBuffers& opencl = buffers[0].second;
  const FrameBuffers& reference = buffers[1].second;
  for (int j = 0; j < 36; ++j) {
    for (int i = 0; i < 64; ++i) EXPECT_EQ(status_at(opencl, i, j), status_at(reference, i, j)) << i << ", " << j;
  }
  const std::uint64_t out_of_steps = reference.rays_with_status(RayStatus::OutOfSteps);
  EXPECT_GT(out_of_steps, 64u * 36u / 10u);
  EXPECT_GT(reference.rays_with_status(RayStatus::OutOfDistance), 64u * 36u / 10u);
  EXPECT_GT(reference.rays_with_status(RayStatus::Hit), 64u * 36u / 10u);
  for (const char* backend : {"opencl", "reference"}) {
    const testing::CommandResult r = testing::run_clmarch(
        {"render", (dir / "scene.yaml").string(), "--backend", backend, "--stats", "-o", (dir / "s.png").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json stats = nlohmann::json::parse(r.out);
    EXPECT_EQ(stats["out_of_steps"].get<std::uint64_t>(), out_of_steps) << backend;
    EXPECT_EQ(stats["out_of_distance"].get<std::uint64_t>(), reference.rays_with_status(RayStatus::OutOfDistance))
        << backend;
  }
  const testing::CommandResult r = testing::run_clmarch(
      {"render", (dir / "scene.yaml").string(), "--set", "shading.view=status", "-o", (dir / "status.exr").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const testing::Image image = testing::read_image(dir / "status.exr");
  for (int j = 0; j < 36; ++j) {
    for (int i = 0; i < 64; ++i) {
      const std::array<float, 3> want = status_color(status_at(reference, i, j));
      for (int c = 0; c < 3; ++c) EXPECT_EQ(image.at(i, j, c), want[c]) << i << ", " << j;
    }
  }
  EXPECT_EQ(status_color(RayStatus::OutOfSteps), (std::array<float, 3>{1.0f, 0.0f, 1.0f})) << "magenta, as documented";
}

}  // namespace
}  // namespace clmarch

// The scene's bounding sphere: every point where a node's field falls below a threshold lies inside
// its bound (sampled against the reference field), spans of rays against closed forms, and renders
// clipped to the bound equal unclipped ones with fewer distance evaluations.
#include "reference/reference_renderer.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_bounds.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <random>

namespace clmarch {
namespace {

using testing::scene_from_yaml;

Node tree(const std::string& sdf_yaml) { return scene_from_yaml("sdf:\n" + sdf_yaml).sdf; }

struct BoundCase {
  const char* name;
  const char* sdf;
};

// Every bounded primitive and operator, with transforms, smooth blends, displacement and step
// factors that change the bound's radius and gain.
const BoundCase kBoundedCases[] = {
    {"sphere", "  sphere: {center: [1, 2, 3], radius: 0.5}"},
    {"box", "  box: {center: [0, 1, 0], half_size: [0.5, 1, 0.25], rotate: [30, 40, 50]}"},
    {"round_box", "  round_box: {half_size: [0.5, 0.3, 0.2], radius: 0.1, translate: [1, 0, 0]}"},
    {"box_frame", "  box_frame: {half_size: [0.6, 0.6, 0.6], thickness: 0.05}"},
    {"torus", "  torus: {major_radius: 1, minor_radius: 0.3, scale: 2, translate: [0, 1, 0]}"},
    {"capsule", "  capsule: {a: [-1, 0, 0], b: [1, 1, 0], radius: 0.2}"},
    {"cylinder", "  cylinder: {radius: 0.4, half_height: 0.8, rotate: [90, 0, 0]}"},
    {"mandelbulb", "  mandelbulb: {power: 8, iterations: 6, bailout: 2, step_factor: 0.8}"},
    {"menger", "  menger: {half_size: 1, iterations: 3, translate: [0.5, 0, 0]}"},
    {"union", "  union:\n    - sphere: {center: [-1, 0, 0], radius: 0.5}\n    - box: {center: [1.5, 0, 0], half_size: [0.3, 0.3, 0.3]}"},
    {"smooth_union",
     "  smooth_union:\n    k: 0.8\n    children:\n      - sphere: {center: [-0.6, 0, 0], radius: 0.5}\n"
     "      - sphere: {center: [0.6, 0, 0], radius: 0.5}"},
    {"intersection", "  intersection:\n    - plane: {normal: [0, 1, 0], offset: 0}\n    - sphere: {radius: 1}"},
    {"smooth_subtraction",
     "  smooth_subtraction:\n    k: 0.3\n    children:\n      - box: {half_size: [1, 1, 1]}\n      - sphere: {radius: 1.2}"},
    {"displace", "  displace:\n    amplitude: 0.2\n    frequency: 5\n    children:\n      - sphere: {radius: 1}"},
};

class NodeBounds : public ::testing::TestWithParam<BoundCase> {};

TEST_P(NodeBounds, HoldEveryPointBelowTheThreshold) {
  const Node node = tree(GetParam().sdf);
  const std::optional<BoundingSphere> bound = node_bounds(node);
  ASSERT_TRUE(bound.has_value());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  int below = 0;
  for (int i = 0; i < 40000; ++i) {
    const glm::dvec3 p(coordinate(random), coordinate(random), coordinate(random));
    for (double tau : {1e-3, 0.1, 0.5}) {
      if (reference_distance(node, p) >= tau) continue;
      ++below;
      // The bound's promise, with a relative allowance for double rounding only.
      EXPECT_LT(glm::length(p - bound->center), bound->radius + bound->gain * tau + 1e-9)
          << "tau " << tau << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
  }
  EXPECT_GT(below, 50) << "the sample must reach the surface for the test to mean something";
}

TEST_P(NodeBounds, AreTightEnoughToHelp) {
  // A bound larger than twice the sampled extent of the shape would clip nothing useful.
  const Node node = tree(GetParam().sdf);
  const BoundingSphere bound = *node_bounds(node);
  EXPECT_LT(bound.radius, 6.0);
}

INSTANTIATE_TEST_SUITE_P(Kinds, NodeBounds, ::testing::ValuesIn(kBoundedCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(NodeBounds, UnboundedFieldsHaveNone) {
  EXPECT_FALSE(node_bounds(tree("  plane: {normal: [0, 1, 0], offset: 0}")));
  EXPECT_FALSE(node_bounds(tree("  terrain: {amplitude: 1}")));
  EXPECT_FALSE(node_bounds(tree("  repeat:\n    period: [2, 0, 0]\n    children:\n      - sphere: {radius: 0.5}")));
  EXPECT_FALSE(node_bounds(tree("  union:\n    - sphere: {radius: 1}\n    - plane: {normal: [0, 1, 0]}")));
}

TEST(NodeBounds, StepFactorAndDisplacementRaiseTheGain) {
  EXPECT_DOUBLE_EQ(node_bounds(tree("  sphere: {radius: 1, step_factor: 0.5}"))->gain, 2.0);
  const Node displaced = tree("  displace:\n    amplitude: 0.1\n    frequency: 2\n    children:\n      - sphere: {radius: 1}");
  const BoundingSphere b = *node_bounds(displaced);
  EXPECT_DOUBLE_EQ(b.radius, 1.1);
  EXPECT_DOUBLE_EQ(b.gain, displacement_lipschitz(displaced));
}

TEST(RaySphereSpan, MatchesTheClosedForm) {
  const BoundingSphere unit{glm::dvec3(0.0, 0.0, 5.0), 1.0, 1.0};
  const auto through = ray_sphere_span(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), unit);
  ASSERT_TRUE(through);
  EXPECT_DOUBLE_EQ(through->t_enter, 4.0);
  EXPECT_DOUBLE_EQ(through->t_exit, 6.0);
  // Offset by 0.6 sideways: the chord is 2 sqrt(1 - 0.36) = 1.6 long.
  const auto chord = ray_sphere_span(glm::dvec3(0.6, 0.0, 0.0), glm::dvec3(0.0, 0.0, 1.0), unit);
  ASSERT_TRUE(chord);
  EXPECT_NEAR(chord->t_exit - chord->t_enter, 1.6, 1e-12);
  EXPECT_FALSE(ray_sphere_span(glm::dvec3(1.01, 0.0, 0.0), glm::dvec3(0.0, 0.0, 1.0), unit));
  const auto inside = ray_sphere_span(glm::dvec3(0.0, 0.0, 5.0), glm::dvec3(1.0, 0.0, 0.0), unit);
  ASSERT_TRUE(inside);
  EXPECT_DOUBLE_EQ(inside->t_enter, -1.0);
}

TEST(CameraRayBounds, GrowByThresholdAndGlowAndStayOffForTilingAndNone) {
  const std::string sphere = "sdf: {sphere: {radius: 1}}\nrender: {epsilon: 0.01}\n";
  const BoundingSphere plain = *camera_ray_bounds(scene_from_yaml(sphere));
  EXPECT_GE(plain.radius, 1.01);
  const BoundingSphere glowing = *camera_ray_bounds(scene_from_yaml(sphere + "shading: {glow: {radius: 0.3}}\n"));
  EXPECT_NEAR(glowing.radius - plain.radius, 0.3, 1e-12);
  EXPECT_FALSE(camera_ray_bounds(scene_from_yaml(sphere + "tiling: {cell: [4, 4, 4]}\n")));
  Scene off = scene_from_yaml(sphere);
  off.render.bounds = SceneBounds::None;
  EXPECT_FALSE(camera_ray_bounds(off));
}

// Clipping to the bound changes where the march starts and stops, never what it finds: hit masks
// agree, depths agree within the hit threshold (both stop within epsilon of the same surface), and
// pixels whose rays miss the sphere take no step at all.
void expect_clipping_keeps_the_image(const FrameBuffers& clipped, const FrameBuffers& full, double epsilon) {
  const auto& depth_clipped = clipped.plane(Channel::Depth);
  const auto& depth_full = full.plane(Channel::Depth);
  double steps_clipped = 0.0, steps_full = 0.0;
  int idle = 0;
  for (std::size_t i = 0; i < depth_full.size(); ++i) {
    ASSERT_EQ(std::isinf(depth_clipped[i]), std::isinf(depth_full[i])) << "pixel " << i;
    if (!std::isinf(depth_full[i])) {
      EXPECT_NEAR(depth_clipped[i], depth_full[i], 2.0 * epsilon) << "pixel " << i;
    }
    steps_clipped += clipped.plane(Channel::Steps)[i];
    steps_full += full.plane(Channel::Steps)[i];
    idle += clipped.plane(Channel::Steps)[i] == 0.0f;
  }
  EXPECT_LT(steps_clipped, 0.9 * steps_full);
  EXPECT_GT(idle, 0) << "rays that miss the sphere must not march";
}

const char* kClippedScene =
    "camera: {position: [0, 1, 6], look_at: [0, 0, 0], fov: 50}\n"
    "render: {width: 48, height: 27, epsilon: 1.0e-4, max_distance: 50}\n"
    "sdf:\n  smooth_union:\n    k: 0.3\n    children:\n      - torus: {major_radius: 1, minor_radius: 0.3}\n"
    "      - sphere: {center: [0, 0.5, 0], radius: 0.6}\n";

TEST(CameraRayBounds, ReferenceRenderEqualsTheUnclippedOne) {
  Scene scene = scene_from_yaml(kClippedScene);
  const FrameBuffers clipped = render_reference(scene);
  scene.render.bounds = SceneBounds::None;
  expect_clipping_keeps_the_image(clipped, render_reference(scene), scene.render.epsilon);
}

TEST(CameraRayBounds, OpenClRenderEqualsTheUnclippedOne) {
  Scene scene = scene_from_yaml(kClippedScene);
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  const FrameBuffers clipped = render_opencl(scene, options).buffers;
  scene.render.bounds = SceneBounds::None;
  expect_clipping_keeps_the_image(clipped, render_opencl(scene, options).buffers, scene.render.epsilon);
}

TEST(CameraRayBounds, TilesSkippedWholeByDepthProgramsAreMissesOfTheShadedOnes) {
  // Programs without shading skip a 4x4 tile when one scalar test shows none of its rays meets the
  // bounding sphere, and write its pixels as misses without marching. The shaded program marches
  // every tile, so depth, steps and normals must be the same pixel for pixel: from close (the
  // sphere fills the view) to far (the sphere covers a few pixels, where a tile's spread matters
  // most), and with chunks of 8 rows in one buffer, so that a tile left unwritten would keep an
  // earlier chunk's values. Planes a program does not compute read back as 0.
  const std::vector<std::pair<std::string, std::string>> cameras = {
      {"[0, 0.5, 2.2]", "50"}, {"[-2, 4, 4]", "50"}, {"[30, 12, -25]", "20"}, {"[150, 40, 90]", "4"}};
  const auto all_zero = [](const std::vector<float>& plane) {
    return std::all_of(plane.begin(), plane.end(), [](float v) { return v == 0.0f; });
  };
  for (const auto& [position, fov] : cameras) {
    Scene scene = scene_from_yaml("camera: {position: " + position + ", look_at: [0.3, 0, 0.1], fov: " + fov + "}\n"
                                  "render: {width: 61, height: 45, max_distance: 1000}\nsdf: {torus: {}}\n");
    OpenClOptions shaded, depth, normals;
    shaded.purpose = KernelPurpose::Shaded;
    depth.purpose = KernelPurpose::DepthSteps;
    depth.max_chunk_pixels = 61 * 8;
    normals.purpose = KernelPurpose::Normals;
    normals.max_chunk_pixels = 61 * 8;
    const FrameBuffers a = render_opencl(scene, shaded).buffers;
    const FrameBuffers b = render_opencl(scene, depth).buffers;
    const FrameBuffers n = render_opencl(scene, normals).buffers;
    EXPECT_EQ(a.plane(Channel::Steps), b.plane(Channel::Steps)) << position;
    EXPECT_EQ(a.plane(Channel::Depth), b.plane(Channel::Depth)) << position;
    EXPECT_EQ(a.plane(Channel::Steps), n.plane(Channel::Steps)) << position;
    EXPECT_EQ(a.plane(Channel::Depth), n.plane(Channel::Depth)) << position;
    for (Channel c : {Channel::NX, Channel::NY, Channel::NZ}) {
      EXPECT_EQ(a.plane(c), n.plane(c)) << position;
      EXPECT_TRUE(all_zero(b.plane(c))) << position;
    }
    for (Channel c : {Channel::R, Channel::G, Channel::B, Channel::WallSteps}) {
      EXPECT_TRUE(all_zero(b.plane(c))) << position;
      EXPECT_TRUE(all_zero(n.plane(c))) << position;
    }
    EXPECT_GT(std::count_if(a.plane(Channel::Depth).begin(), a.plane(Channel::Depth).end(),
                            [](float d) { return std::isfinite(d); }),
              0)
        << position;
  }
}

}  // namespace
}  // namespace clmarch

// The scene's bounding sphere: every point where a node's field falls below a threshold lies inside
// its bound (sampled against the reference field), spans of rays against closed forms, and renders
// clipped to the bound equal unclipped ones with fewer distance evaluations.
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "reference/reference_sdf.hpp"
#include "render/device_inputs.hpp"
#include "render/dispatch_plan.hpp"
#include "render/live_tiles.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/scene_box.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
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
    {"cone", "  cone: {center: [0, 1, 0], angle: 30, height: 1.5}"},
    {"cone_wide", "  cone: {angle: 70, height: 0.5, rotate: [10, 0, 0]}"},
    {"rounded_cylinder",
     "  rounded_cylinder: {radius: 0.6, half_height: 0.3, edge_radius: 0.1, translate: [0, 0.5, 0]}"},
    {"round_cone", "  round_cone: {a: [-1, 0, 0], b: [1, 0.5, 0], radius_a: 0.5, radius_b: 0.2}"},
    {"capped_cylinder", "  capped_cylinder: {a: [-1, 0, 0.5], b: [1, 0.5, 0], radius: 0.3}"},
    {"frustum", "  frustum: {a: [-1, 0, 0.5], b: [1, 0.5, 0], radius_a: 0.6, radius_b: 0.1}"},
    {"capped_torus", "  capped_torus: {angle: 100, major_radius: 1, minor_radius: 0.2, rotate: [30, 0, 0]}"},
    {"link", "  link: {half_length: 0.5, major_radius: 0.5, minor_radius: 0.15}"},
    {"cut_sphere", "  cut_sphere: {radius: 1, cut_height: 0.5}"},
    {"cut_sphere_low", "  cut_sphere: {radius: 1, cut_height: -0.7, translate: [0, 1, 0]}"},
    {"pyramid", "  pyramid: {half_width: 0.5, height: 1.5}"},
    {"pyramid_flat", "  pyramid: {half_width: 1.5, height: 0.5}"},
    {"triangle", "  triangle: {a: [0, 0, 0], b: [2, 0, 1], c: [0, 1.5, -1], thickness: 0.05}"},
    {"quad", "  quad: {a: [-1, 0, -1], b: [1, 0.5, -1], c: [1, 0.5, 1], d: [-1, 0, 1], thickness: 0.05}"},
    {"triangular_prism", "  triangular_prism: {radius: 1, half_length: 0.5}"},
    {"solid_angle", "  solid_angle: {angle: 50, radius: 1.2}"},
    {"cut_hollow_sphere", "  cut_hollow_sphere: {radius: 1, cut_height: 0.3, thickness: 0.1}"},
    {"cut_hollow_sphere_shallow", "  cut_hollow_sphere: {radius: 1, cut_height: -0.6, thickness: 0.1}"},
    {"death_star", "  death_star: {radius: 1, carve_radius: 0.7, carve_distance: 1.1}"},
    {"rhombus", "  rhombus: {half_width: 1, half_depth: 0.5, half_height: 0.2, corner_radius: 0.1}"},
    {"mandelbulb", "  mandelbulb: {power: 8, iterations: 6, bailout: 2, step_factor: 0.8}"},
    {"menger", "  menger: {half_size: 1, iterations: 3, translate: [0.5, 0, 0]}"},
    {"menger_turned", "  menger: {half_size: 1, iterations: 2, rotate: [20, 35, 0], scale: 1.5}"},
    {"smooth_intersection_of_boxes",
     "  smooth_intersection:\n    k: 0.3\n    children:\n      - box: {half_size: [2, 0.4, 2]}\n"
     "      - box: {half_size: [0.5, 2, 0.5], rotate: [0, 30, 0]}"},
    {"smooth_subtraction_of_boxes",
     "  smooth_subtraction:\n    k: 0.4\n    children:\n      - box: {half_size: [1.5, 0.5, 1], step_factor: 0.5}\n"
     "      - box: {half_size: [0.5, 2, 0.5]}"},
    {"sierpinski", "  sierpinski: {size: 1.5, iterations: 6, step_factor: 0.8, translate: [0, 0.5, 0]}"},
    {"mandelbox", "  mandelbox: {scale: -1.5, iterations: 8, step_factor: 0.8, translate: [0, 0.5, 0]}"},
    {"julia", "  julia: {c: [-0.2, 0.6, 0.2, 0.1], iterations: 10, step_factor: 0.8}"},
    {"revolve",
     "  revolve:\n    offset: 0.6\n    children: [{rounded_rectangle: {center: [0.3, 0.2, 0], half_width: 0.4, "
     "half_height: 0.6}}]"},
    {"revolve_of_sphere", "  revolve: {offset: 1, children: [{sphere: {center: [0.5, 0, 0.3], radius: 0.6}}]}"},
    {"extrude",
     "  extrude:\n    half_length: 0.8\n    children: [{regular_polygon: {center: [0.4, 0, 3], radius: 1, sides: 5, "
     "rotate: [0, 0, 20], "
     "translate: [0.2, 0.3, 4]}}]"},
    {"extrude_of_segment",
     "  extrude: {half_length: 0.3, children: [{segment: {a: [-1, 0.5, 0], b: [1.5, -0.5, 0], radius: 0.2, scale: "
     "1.5}}]}"},
    {"twist", "  twist: {rate: 60, children: [{box: {center: [0.5, 0, 0], half_size: [0.6, 1.5, 0.3]}}]}"},
    {"bend", "  bend: {rate: -40, children: [{box: {center: [0, 0.4, 0], half_size: [1.5, 0.2, 0.3]}}]}"},
    {"nonuniform_scale",
     "  nonuniform_scale: {factors: [2, 0.5, 1], children: [{torus: {center: [0.5, 0, 0], major_radius: 1, "
     "minor_radius: 0.3}}]}"},
    {"union",
     "  union:\n    - sphere: {center: [-1, 0, 0], radius: 0.5}\n    - box: {center: [1.5, 0, 0], half_size: [0.3, "
     "0.3, 0.3]}"},
    // Each fold of three coincident spheres undershoots the last by up to k / 4: 0.39 k in all.
    {"smooth_union_of_three",
     "  smooth_union:\n    k: 2\n    children: [{sphere: {radius: 0.5}}, {sphere: {radius: 0.5}}, {sphere: {radius: "
     "0.5}}]"},
    {"smooth_union",
     "  smooth_union:\n    k: 0.8\n    children:\n      - sphere: {center: [-0.6, 0, 0], radius: 0.5}\n"
     "      - sphere: {center: [0.6, 0, 0], radius: 0.5}"},
    // The blend's bulge reaches the bound: two coincident spheres blend into one of radius 1 + k/4.
    {"smooth_union_coincident",
     "  smooth_union:\n    k: 0.8\n    children:\n      - sphere: {radius: 1}\n      - sphere: {radius: 1}"},
    {"intersection", "  intersection:\n    - plane: {normal: [0, 1, 0], offset: 0}\n    - sphere: {radius: 1}"},
    {"smooth_subtraction",
     "  smooth_subtraction:\n    k: 0.3\n    children:\n      - box: {half_size: [1, 1, 1]}\n      - sphere: {radius: "
     "1.2}"},
    // The blends' bulges: radius 0.8 across the 0.2 gap between two spheres, and three children (the
    // growth adds up per fold).
    {"union_chamfer",
     "  union_chamfer: {radius: 0.8, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0.6, "
     "0, 0], radius: 0.5}}]}"},
    {"union_chamfer_three",
     "  union_chamfer: {radius: 0.8, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0.6, "
     "0, 0], radius: 0.5}}, {sphere: {center: [0, 0.9, 0], radius: 0.5}}]}"},
    {"union_round",
     "  union_round: {radius: 0.8, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0.6, "
     "0, 0], radius: 0.5}}]}"},
    {"union_round_three",
     "  union_round: {radius: 0.8, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0.6, "
     "0, 0], radius: 0.5}}, {sphere: {center: [0, 0.9, 0], radius: 0.5}}]}"},
    {"union_stairs",
     "  union_stairs: {radius: 0.8, steps: 3, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: "
     "{center: [0.6, 0, 0], radius: 0.5}}]}"},
    {"union_stairs_three",
     "  union_stairs: {radius: 0.8, steps: 2, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: "
     "{center: [0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0, 0.9, 0], radius: 0.5}}]}"},
    {"union_columns",
     "  union_columns: {radius: 0.8, steps: 2, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: "
     "{center: [0.6, 0, 0], radius: 0.5}}]}"},
    {"union_columns_three",
     "  union_columns: {radius: 0.8, steps: 1, children: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: "
     "{center: [0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0, 0.9, 0], radius: 0.5}}]}"},
    {"intersection_chamfer",
     "  intersection_chamfer: {radius: 0.3, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, 1, 0], "
     "radius: 0.8}}]}"},
    {"intersection_round",
     "  intersection_round: {radius: 0.3, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, 1, 0], "
     "radius: 0.8}}]}"},
    {"intersection_stairs",
     "  intersection_stairs: {radius: 0.3, steps: 2, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, "
     "1, 0], radius: 0.8}}]}"},
    {"intersection_columns",
     "  intersection_columns: {radius: 0.3, steps: 2, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, "
     "1, 0], radius: 0.8}}]}"},
    {"difference_chamfer",
     "  difference_chamfer: {radius: 0.3, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, 1, 0], "
     "radius: 0.8}}]}"},
    {"difference_round",
     "  difference_round: {radius: 0.3, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, 1, 0], radius: "
     "0.8}}]}"},
    {"difference_stairs",
     "  difference_stairs: {radius: 0.3, steps: 2, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, 1, "
     "0], radius: 0.8}}]}"},
    {"difference_columns",
     "  difference_columns: {radius: 0.3, steps: 2, children: [{box: {half_size: [1, 1, 1]}}, {sphere: {center: [1, 1, "
     "0], radius: 0.8}}]}"},
    {"xor", "  xor: [{sphere: {center: [-0.6, 0, 0], radius: 0.5}}, {sphere: {center: [0.6, 0, 0], radius: 0.5}}]"},
    {"pipe", "  pipe: {radius: 0.2, children: [{sphere: {radius: 1}}, {plane: {normal: [1, 0, 0], offset: 0.2}}]}"},
    {"pipe_three",
     "  pipe: {radius: 0.2, children: [{plane: {normal: [0, 1, 0]}}, {sphere: {radius: 1}}, {plane: {normal: [1, 0, "
     "0], offset: 0.2}}]}"},
    {"engrave",
     "  engrave: {radius: 0.3, children: [{sphere: {radius: 1}}, {plane: {normal: [1, 0, 0], offset: 0.2}}]}"},
    {"groove",
     "  groove: {ra: 0.3, rb: 0.2, children: [{sphere: {radius: 1}}, {plane: {normal: [1, 0, 0], offset: 0.2}}]}"},
    {"tongue",
     "  tongue: {ra: 0.3, rb: 0.2, children: [{sphere: {radius: 1}}, {plane: {normal: [1, 0, 0], offset: 0.2}}]}"},
    {"tongue_three",
     "  tongue: {ra: 0.3, rb: 0.2, children: [{sphere: {radius: 1}}, {plane: {normal: [1, 0, 0], offset: 0.2}}, "
     "{plane: {normal: [0, 0, 1]}}]}"},
    {"displace", "  displace:\n    amplitude: 0.2\n    frequency: 5\n    children:\n      - sphere: {radius: 1}"},
    // The child's gain scales the amplitude: a child that steps short, and displacement twice.
    {"displace_of_short_steps",
     "  displace:\n    amplitude: 0.5\n    frequency: 3\n    children:\n      - sphere: {radius: 1, step_factor: "
     "0.25}"},
    {"displace_of_displace",
     "  displace:\n    amplitude: 0.3\n    frequency: 3\n    children:\n      - displace:\n          amplitude: 0.3\n"
     "          frequency: 4\n          children:\n            - sphere: {radius: 1}"},
};

class NodeBounds : public ::testing::TestWithParam<BoundCase> {};

/// Calls promise(p, tau) for every point p of a random sample of [-5, 5]^3 where node's field is
/// below tau, for thresholds from 10^-3 to 0.5; expects the sample to reach the surface.
template <typename Promise>
void for_each_point_below(const Node& node, Promise promise) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  int below = 0;
  for (int i = 0; i < 40000; ++i) {
    const glm::dvec3 p(coordinate(random), coordinate(random), coordinate(random));
    for (double tau : {1e-3, 0.1, 0.5}) {
      if (reference_distance(node, p) >= tau) continue;
      ++below;
      promise(p, tau);
    }
  }
  EXPECT_GT(below, 50) << "the sample must reach the surface for the test to mean something";
}

TEST_P(NodeBounds, HoldEveryPointBelowTheThreshold) {
  const Node node = tree(GetParam().sdf);
  const std::optional<BoundingSphere> bound = node_bounds(node);
  ASSERT_TRUE(bound.has_value());
  for_each_point_below(node, [&](const glm::dvec3& p, double tau) {
    // The bound's promise, with a relative allowance for double rounding only.
    EXPECT_LT(glm::length(p - bound->center), bound->radius + bound->gain * tau + 1e-9)
        << "tau " << tau << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
  });
}

TEST_P(NodeBounds, BoxesHoldEveryPointBelowTheThreshold) {
  const Node node = tree(GetParam().sdf);
  const std::optional<BoundingBox> box = node_box(node);
  ASSERT_TRUE(box.has_value());
  for_each_point_below(node, [&](const glm::dvec3& p, double tau) {
    const glm::dvec3 margin(box->gain * tau + 1e-9);
    EXPECT_TRUE(glm::all(glm::greaterThan(p, box->low - margin)) && glm::all(glm::lessThan(p, box->high + margin)))
        << "tau " << tau << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
  });
}

TEST_P(NodeBounds, AreTightEnoughToHelp) {
  // A bound larger than twice the sampled extent of the shape would clip nothing useful.
  const Node node = tree(GetParam().sdf);
  const BoundingSphere bound = *node_bounds(node);
  EXPECT_LT(bound.radius, 6.0);
}

INSTANTIATE_TEST_SUITE_P(Kinds, NodeBounds, ::testing::ValuesIn(kBoundedCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(NodeBoxes, FollowTheShapesWhereTheyAreBoxy) {
  // A box turned 90 degrees about y swaps its x and z half sizes; scaled, moved.
  const BoundingBox turned =
      *node_box(tree("  box: {half_size: [1, 2, 3], rotate: [0, 90, 0], scale: 2, translate: [1, 0, 0]}"));
  EXPECT_NEAR(turned.low.x, 1.0 - 6.0, 1e-12);
  EXPECT_NEAR(turned.high.y, 4.0, 1e-12);
  EXPECT_NEAR(turned.high.z, 2.0, 1e-12);
  // The Menger sponge fills its cube; the torus its flat box.
  const BoundingBox sponge = *node_box(tree("  menger: {center: [0, 1, 0], half_size: 2}"));
  EXPECT_DOUBLE_EQ(sponge.low.y, -1.0);
  EXPECT_DOUBLE_EQ(sponge.high.x, 2.0);
  const BoundingBox ring = *node_box(tree("  torus: {major_radius: 1, minor_radius: 0.25}"));
  EXPECT_DOUBLE_EQ(ring.high.y, 0.25);
  EXPECT_DOUBLE_EQ(ring.high.x, 1.25);
  // Unions span their children; intersections keep what all share; subtractions the first.
  const BoundingBox both =
      *node_box(tree("  union:\n    - box: {center: [-2, 0, 0], half_size: [0.5, 0.5, 0.5]}\n"
                     "    - box: {center: [2, 0, 0], half_size: [0.5, 0.5, 0.5]}"));
  EXPECT_DOUBLE_EQ(both.low.x, -2.5);
  EXPECT_DOUBLE_EQ(both.high.x, 2.5);
  EXPECT_DOUBLE_EQ(both.high.y, 0.5);
  const BoundingBox common =
      *node_box(tree("  intersection:\n    - box: {half_size: [2, 0.5, 2]}\n    - sphere: {radius: 1}"));
  EXPECT_DOUBLE_EQ(common.high.y, 0.5);
  EXPECT_DOUBLE_EQ(common.high.x, 1.0);
  const BoundingBox cut =
      *node_box(tree("  subtraction:\n    - box: {half_size: [1, 0.5, 1]}\n    - sphere: {radius: 3}"));
  EXPECT_DOUBLE_EQ(cut.high.y, 0.5);
  // A kind without a box of its own has its sphere's cube.
  const BoundingBox ball = *node_box(tree("  sphere: {center: [1, 0, 0], radius: 0.5}"));
  EXPECT_DOUBLE_EQ(ball.low.x, 0.5);
  EXPECT_DOUBLE_EQ(ball.high.z, 0.5);
  EXPECT_FALSE(node_box(tree("  plane: {normal: [0, 1, 0], offset: 0}")));
}

TEST(NodeBoxes, RayBoxSpanBySlabs) {
  const BoundingBox unit{glm::dvec3(-1.0), glm::dvec3(1.0)};
  const RaySpan through = ray_box_span({-3, 0.5, 0}, {1, 0, 0}, unit);
  EXPECT_DOUBLE_EQ(through.t_enter, 2.0);
  EXPECT_DOUBLE_EQ(through.t_exit, 4.0);
  // Parallel to the y and z slabs, outside the y one: never inside.
  const RaySpan beside = ray_box_span({-3, 1.5, 0}, {1, 0, 0}, unit);
  EXPECT_GT(beside.t_enter, beside.t_exit);
  const glm::dvec3 diagonal = glm::normalize(glm::dvec3(1, 1, 1));
  const RaySpan corner = ray_box_span({-2, -2, -2}, diagonal, unit);
  EXPECT_NEAR(corner.t_enter, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(corner.t_exit, 3.0 * std::sqrt(3.0), 1e-12);
}

TEST(CameraRayBoxes, TheKeyTakesBoxSphereOrNone) {
  EXPECT_EQ(scene_from_yaml("sdf: {sphere: {}}\n").render.bounds, RayBounds::Box);
  EXPECT_EQ(scene_from_yaml("render: {bounds: sphere}\nsdf: {sphere: {}}\n").render.bounds, RayBounds::Sphere);
  EXPECT_EQ(scene_from_yaml("render: {bounds: none}\nsdf: {sphere: {}}\n").render.bounds, RayBounds::None);
  EXPECT_EQ(testing::error_of("render: {bounds: cube}\nsdf: {sphere: {}}\n"),
            "s.yaml:1:18: render.bounds must be one of none, sphere, box (got 'cube')");
}

TEST(CameraRayBoxes, BoxByDefaultAndOnlyThen) {
  const std::string cube = "sdf: {box: {half_size: [1, 1, 1]}}\nrender: {epsilon: 0.01}\n";
  const BoundingBox grown = *camera_ray_box(scene_from_yaml(cube));
  EXPECT_GE(grown.high.x, 1.01);
  EXPECT_LT(grown.high.x, 1.02);
  Scene sphere_only = scene_from_yaml(cube);
  sphere_only.render.bounds = RayBounds::Sphere;
  EXPECT_FALSE(camera_ray_box(sphere_only));
  EXPECT_TRUE(camera_ray_bounds(sphere_only));
  EXPECT_FALSE(camera_ray_box(scene_from_yaml(cube + "tiling: {cell: [4, 4, 4]}\n")));
  EXPECT_FALSE(camera_ray_box(scene_from_yaml(cube + "shading: {step_ao: 300}\n")));
}

TEST(NodeBounds, TwoSpheresHaveTheirSmallestEnclosingSphere) {
  // Spheres of radius 0.5 at x = -1 and 1 at x = 2: the enclosing sphere spans x in [-1.5, 3].
  const BoundingSphere bound = *node_bounds(
      tree("  union:\n    - sphere: {center: [-1, 0, 0], radius: 0.5}\n    - sphere: {center: [2, 0, 0], radius: 1}"));
  EXPECT_NEAR(bound.center.x, 0.75, 1e-12);
  EXPECT_NEAR(glm::length(glm::dvec3(0, bound.center.y, bound.center.z)), 0.0, 1e-12);
  EXPECT_NEAR(bound.radius, 2.25, 1e-12);
}

TEST(NodeBounds, UnboundedFieldsHaveNone) {
  EXPECT_FALSE(node_bounds(tree("  plane: {normal: [0, 1, 0], offset: 0}")));
  EXPECT_FALSE(node_bounds(tree("  terrain: {amplitude: 1}")));
  EXPECT_FALSE(node_bounds(tree("  repeat:\n    period: [2, 0, 0]\n    children:\n      - sphere: {radius: 0.5}")));
  EXPECT_FALSE(node_bounds(tree("  union:\n    - sphere: {radius: 1}\n    - plane: {normal: [0, 1, 0]}")));
}

TEST(NodeBounds, StepFactorAndDisplacementRaiseTheGain) {
  EXPECT_DOUBLE_EQ(node_bounds(tree("  sphere: {radius: 1, step_factor: 0.5}"))->gain, 2.0);
  const Node displaced =
      tree("  displace:\n    amplitude: 0.1\n    frequency: 2\n    children:\n      - sphere: {radius: 1}");
  const BoundingSphere b = *node_bounds(displaced);
  EXPECT_DOUBLE_EQ(b.radius, 1.1);
  EXPECT_DOUBLE_EQ(b.gain, displacement_lipschitz(displaced));
  // Under a child whose field is scaled down 4×, the amplitude reaches 4× as far.
  const BoundingSphere short_steps =
      *node_bounds(tree("  displace:\n    amplitude: 0.1\n    frequency: 2\n    children:\n      - sphere: {radius: 1, "
                        "step_factor: 0.25}"));
  EXPECT_DOUBLE_EQ(short_steps.radius, 1.4);
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
  off.render.bounds = RayBounds::None;
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
  scene.render.bounds = RayBounds::None;
  expect_clipping_keeps_the_image(clipped, render_reference(scene), scene.render.epsilon);
}

TEST(CameraRayBounds, OpenClRenderEqualsTheUnclippedOne) {
  Scene scene = scene_from_yaml(kClippedScene);
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  const FrameBuffers clipped = render_opencl(scene, options).buffers;
  scene.render.bounds = RayBounds::None;
  expect_clipping_keeps_the_image(clipped, render_opencl(scene, options).buffers, scene.render.epsilon);
}

/// Renders scene with its bounds (the default: sphere and box) and without, and expects the same
/// hits and, but at 1 % of them, colors within half a step of 8 bits.
void expect_bounds_keep_the_colors(Scene scene) {
  ASSERT_TRUE(camera_ray_bounds(scene));
  const FrameBuffers clipped = render_opencl(scene, OpenClOptions{}).buffers;
  scene.render.bounds = RayBounds::None;
  const FrameBuffers full = render_opencl(scene, OpenClOptions{}).buffers;
  int hits = 0, off = 0;
  for (int j = 0; j < full.height; ++j) {
    for (int i = 0; i < full.width; ++i) {
      ASSERT_EQ(std::isinf(clipped.at(Channel::Depth, i, j)), std::isinf(full.at(Channel::Depth, i, j)))
          << i << ", " << j;
      if (std::isinf(full.at(Channel::Depth, i, j))) continue;
      ++hits;
      double diff = 0.0;
      for (Channel c : {Channel::R, Channel::G, Channel::B})
        diff = std::max(diff, double(std::abs(clipped.at(c, i, j) - full.at(c, i, j))));
      off += diff > 0.5 / 255.0;
    }
  }
  EXPECT_GT(hits, full.width * full.height / 10);
  EXPECT_LE(off, hits / 100) << "pixels whose color moved by more than half a step of 8 bits";
}

TEST(SecondaryRayBounds, ShadowsAndMirrorsMatchTheUnclippedOnes) {
  // Shadow rays (soft, from a point and a directional light) and mirror rays march inside the
  // scene's bounds as camera rays do; nothing lies outside them, so the picture is the unclipped
  // one but where a shadow ray grazes a surface (a hit on the other side of an edge). A sphere
  // clipped about the wrong point would cut shadows short and darken or light whole areas.
  expect_bounds_keep_the_colors(
      scene_from_yaml("camera: {position: [2.5, 2, 4], look_at: [0, 0.3, 0], fov: 45}\n"
                      "render: {width: 64, height: 48}\n"
                      "sdf:\n  union:\n    children:\n"
                      "      - box: {center: [0, -0.6, 0], half_size: [2, 0.1, 2], reflectivity: 0.5}\n"
                      "      - sphere: {center: [0, 0.3, 0], radius: 0.7, reflectivity: 0.3}\n"
                      "      - torus: {major_radius: 0.5, minor_radius: 0.15, translate: [1.2, -0.35, 0.8]}\n"
                      "lights:\n"
                      "  - point: {position: [3, 4, 2], intensity: 0.8, color: [1, 1, 1]}\n"
                      "  - directional: {direction: [-0.6, 1, 0.3], intensity: 0.6, color: [1, 1, 1]}\n"
                      "shading: {shadows: {mode: soft, k: 8}, reflections: 2, background: [0.2, 0.3, 0.4]}\n"));
}

TEST(SecondaryRayBounds, SoftShadowsGoOnWhileTheirPenumbraCouldFall) {
  // The Menger sponge's box is its surface: soft shadows' rays leave it through the holes of its
  // faces and run on along them, where their penumbra keeps falling. Cut at the box, a fifth of the
  // lit pixels came out too bright against the reference's shading of the same hits, whose shadow
  // rays march to their ends (march_past_bounds carries them on).
  const Scene scene = scene_from_yaml(
      "camera: {position: [3, 2.5, 3.5], look_at: [0, 0, 0], fov: 45}\n"
      "render: {width: 96, height: 54, epsilon: 1.0e-4}\n"
      "sdf: {menger: {half_size: 1, iterations: 3, color: [0.85, 0.8, 0.7]}}\n"
      "lights:\n  - directional: {direction: [0.8, 0.6, 0.3], color: [1, 1, 1], intensity: 1}\n"
      "shading: {model: lambert, ambient: 0.1, diffuse: 0.9, shadows: {mode: soft, k: 8, min_t: 0.01, max_t: 10, "
      "max_steps: 128}}\n");
  ASSERT_TRUE(camera_ray_box(scene));
  const FrameBuffers opencl = render_opencl(scene, OpenClOptions{}).buffers;
  const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
  EXPECT_TRUE(report.passed()) << report.to_text();
  EXPECT_LE(report.ratios.shading_p99, 0.1);
}

// With the box as well as the sphere (the default) camera rays take fewer steps than with the
// sphere alone around a boxy shape, and find the same surface; the reference clips alike, so
// `clmarch check` agrees on the steps.
TEST(CameraRayBoxes, FewerStepsSameImageAndTheReferenceAgrees) {
  Scene scene = scene_from_yaml(
      "camera: {position: [3, 2.5, 3.5], look_at: [0, 0, 0], fov: 45}\n"
      "render: {width: 64, height: 36}\n"
      "sdf: {menger: {half_size: 1, iterations: 2}}\n");
  const CheckReport report = cross_check(scene, render_opencl(scene, OpenClOptions{}).buffers, render_reference(scene));
  EXPECT_TRUE(report.passed()) << report.to_text();
  EXPECT_LE(report.steps_diff_mean, 0.05);
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  const FrameBuffers boxed = render_opencl(scene, options).buffers;
  scene.render.bounds = RayBounds::Sphere;
  expect_clipping_keeps_the_image(boxed, render_opencl(scene, options).buffers, scene.render.epsilon);
}

TEST(CameraRayBounds, TilesSkippedWholeByDepthProgramsAreMissesOfTheShadedOnes) {
  // Programs without shading skip a 4x4 tile when one scalar test shows none of its rays meets the
  // bounding sphere, and write its pixels as misses without marching. The shaded program marches
  // every tile, so depth, steps and normals must be the same pixel for pixel: from close (the
  // sphere fills the view) to far (the sphere covers a few pixels, where a tile's spread matters
  // most), and with chunks of 8 rows in one buffer, so that a tile left unwritten would keep an
  // earlier chunk's values. Planes a program does not compute read back as 0.
  // Also with the sphere at each edge and corner of the view (where the host's range of live tiles
  // ends), behind the camera, around it, and seen through a wide lens.
  struct View {
    const char* position;
    const char* look_at;
    const char* fov;
  };
  const View views[] = {{"[0, 0.5, 2.2]", "[0.3, 0, 0.1]", "50"}, {"[-2, 4, 4]", "[0.3, 0, 0.1]", "50"},
                        {"[30, 12, -25]", "[0.3, 0, 0.1]", "20"}, {"[150, 40, 90]", "[0.3, 0, 0.1]", "4"},
                        {"[0, 0, 6]", "[2.6, 0, 0]", "50"},       {"[0, 0, 6]", "[-2.2, 1.7, 0]", "50"},
                        {"[0, 0, 6]", "[0, -2.1, 0]", "50"},      {"[0, 0, 6]", "[0, 0, 12]", "50"},
                        {"[0.2, 0.1, 0.3]", "[3, 1, 2]", "50"},   {"[0, 3, 2]", "[0, 2.2, -1]", "150"}};
  const auto all_zero = [](const std::vector<float>& plane) {
    return std::all_of(plane.begin(), plane.end(), [](float v) { return v == 0.0f; });
  };
  int views_with_hits = 0;
  for (const View& view : views) {
    const std::string position = std::string(view.position) + " looking at " + view.look_at;
    Scene scene = scene_from_yaml(std::string("camera: {position: ") + view.position + ", look_at: " + view.look_at +
                                  ", fov: " + view.fov +
                                  "}\n"
                                  "render: {width: 61, height: 45, max_distance: 1000}\nsdf: {torus: {}}\n");
    // Tiles of 4x4 (16 lanes) and of 4x2 (8 lanes): the tile test finds its row by the tile height.
    for (int lanes : {8, 16}) {
      OpenClOptions shaded, depth, normals;
      shaded.purpose = KernelPurpose::Shaded;
      shaded.lanes = depth.lanes = normals.lanes = lanes;
      depth.purpose = KernelPurpose::DepthSteps;
      depth.max_chunk_pixels = 61 * 8;
      normals.purpose = KernelPurpose::Normals;
      normals.max_chunk_pixels = 61 * 8;
      const std::string where = position + ", lanes " + std::to_string(lanes);
      const FrameBuffers a = render_opencl(scene, shaded).buffers;
      const FrameBuffers b = render_opencl(scene, depth).buffers;
      const FrameBuffers n = render_opencl(scene, normals).buffers;
      EXPECT_EQ(a.plane(Channel::Steps), b.plane(Channel::Steps)) << where;
      EXPECT_EQ(a.plane(Channel::Depth), b.plane(Channel::Depth)) << where;
      EXPECT_EQ(a.plane(Channel::Steps), n.plane(Channel::Steps)) << where;
      EXPECT_EQ(a.plane(Channel::Depth), n.plane(Channel::Depth)) << where;
      for (Channel c : {Channel::NX, Channel::NY, Channel::NZ}) {
        EXPECT_EQ(a.plane(c), n.plane(c)) << where;
        EXPECT_TRUE(all_zero(b.plane(c))) << where;
      }
      for (Channel c : {Channel::R, Channel::G, Channel::B, Channel::WallSteps}) {
        EXPECT_TRUE(all_zero(b.plane(c))) << where;
        EXPECT_TRUE(all_zero(n.plane(c))) << where;
      }
      const std::vector<float>& depths = a.plane(Channel::Depth);
      if (std::any_of(depths.begin(), depths.end(), [](float d) { return std::isfinite(d); })) ++views_with_hits;
    }
  }
  // All but the view away from the torus see it, at both widths.
  EXPECT_EQ(views_with_hits, 18);
}

// The kernel's scalar tile test as the device computes it, in float from the frame's parameters
// (kernels/march.cl, tile_misses_bounds after the range): whether the tile may meet the sphere.
bool tile_test_passes(const MarchParams& p, int column, int row, int tile_width, int tile_height) {
  const float x = static_cast<float>(column * tile_width) + 0.5f * static_cast<float>(tile_width);
  const float y = static_cast<float>(row * tile_height) + 0.5f * static_cast<float>(tile_height);
  const float sx = x * (2.0f / static_cast<float>(p.width)) - 1.0f;
  const float sy = 1.0f - y * (2.0f / static_cast<float>(p.height));
  float q[3], c[3];
  for (int i = 0; i < 3; ++i) {
    q[i] = p.forward.s[i] + sx * p.right_extent.s[i] + sy * p.up_extent.s[i];
    c[i] = p.bounds.s[i];
  }
  const float cross[3] = {c[1] * q[2] - c[2] * q[1], c[2] * q[0] - c[0] * q[2], c[0] * q[1] - c[1] * q[0]};
  return cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2] <=
         p.tile_reach.s[0] * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
}

TEST(CameraRayBounds, LiveTileRangeHoldsEveryTileTheKernelsTestPasses) {
  // Random cameras around a unit sphere of random size and place, close and far, narrow and wide:
  // the host's range must hold every tile the kernel's own float test lets through, or those tiles
  // would be written as misses. The range must also leave out most of the image when the sphere
  // covers little of it, or it would buy nothing.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int ranges_smaller_than_the_image = 0, views_with_live_tiles = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double distance = std::pow(10.0, 0.3 + 2.5 * (unit(rng) + 1.0) / 2.0);
    const glm::dvec3 position = glm::dvec3(unit(rng), unit(rng), unit(rng)) * distance;
    const glm::dvec3 look_at(unit(rng) * distance * 0.3, unit(rng) * distance * 0.3, unit(rng) * distance * 0.3);
    const double fov = 2.0 + 85.0 * (unit(rng) + 1.0);
    const std::string yaml = fmt::format(
        "camera: {{position: [{}, {}, {}], look_at: [{}, {}, {}], fov: {}}}\n"
        "render: {{width: {}, height: {}, max_distance: 1e5}}\nsdf: {{sphere: {{center: [{}, {}, {}], radius: {}}}}}\n",
        position.x, position.y, position.z, look_at.x, look_at.y, look_at.z, fov, 37 + trial % 90,
        29 + (trial * 7) % 70, unit(rng), unit(rng), unit(rng), 0.05 + (unit(rng) + 1.0));
    const Scene scene = scene_from_yaml(yaml);
    PreparedProgram program;
    program.lanes = 16;
    program.packets_per_item = 2;
    const Dispatch dispatch =
        plan_tile_dispatch(program, scene.render.width, scene.render.height, std::size_t{1} << 20);
    const MarchParams params = march_params(scene, dispatch);
    ASSERT_GT(params.bounds.s[3], 0.0f) << yaml;
    const int columns = (scene.render.width + 3) / 4, rows = (scene.render.height + 3) / 4;
    int live = 0;
    for (int row = 0; row < rows; ++row) {
      for (int column = 0; column < columns; ++column) {
        if (!tile_test_passes(params, column, row, 4, 4)) continue;
        ++live;
        EXPECT_TRUE(column >= params.live_columns[0] && column <= params.live_columns[1] &&
                    row >= params.live_rows[0] && row <= params.live_rows[1])
            << "tile " << column << ", " << row << " outside columns " << params.live_columns[0] << ".."
            << params.live_columns[1] << ", rows " << params.live_rows[0] << ".." << params.live_rows[1] << " of\n"
            << yaml;
      }
    }
    if (live > 0) ++views_with_live_tiles;
    const int range_tiles = std::max(0, params.live_columns[1] - params.live_columns[0] + 1) *
                            std::max(0, params.live_rows[1] - params.live_rows[0] + 1);
    if (range_tiles < columns * rows / 2) ++ranges_smaller_than_the_image;
  }
  EXPECT_GT(views_with_live_tiles, 100);
  EXPECT_GT(ranges_smaller_than_the_image, 100);
}

TEST(CameraRayBounds, LiveTilesOfASphereAheadAreItsDisc) {
  // A sphere of radius 1 straight ahead at distance 10, 90 degrees of view on 400 x 400 pixels in
  // 4 x 4 tiles: its disc has a radius of tan(asin(0.1)) / tan(45 deg) * 200 = 20.1 pixels around
  // the centre (200, 200), 5.03 tiles, and the range holds the tiles whose centre lies in it
  // (columns and rows 45 to 54) and one more on each side.
  Scene scene = scene_from_yaml(
      "camera: {position: [0, 0, 10], look_at: [0, 0, 0], fov: 90}\n"
      "render: {width: 400, height: 400}\nsdf: {sphere: {radius: 1}}\n");
  const CameraBasis basis = camera_basis(scene.camera, 400, 400);
  const TileRange live = live_tiles(basis, glm::dvec3(0, 0, 10), 1.0, 4, 4);
  const double disc_tiles = std::tan(std::asin(0.1)) * 200.0 / 4.0;
  for (const auto& [first, last] :
       {std::pair{live.first_column, live.last_column}, std::pair{live.first_row, live.last_row}}) {
    EXPECT_EQ(first + last, 99) << "centred on tile 49.5";
    EXPECT_EQ(first, static_cast<int>(std::ceil(49.5 - disc_tiles)) - 1);
  }
  // A camera within reach of the centre: every tile.
  const TileRange around = live_tiles(basis, glm::dvec3(0, 0, 0.5), 1.0, 4, 4);
  EXPECT_EQ(around.first_column, 0);
  EXPECT_EQ(around.last_column, 99);
  EXPECT_EQ(around.first_row, 0);
  EXPECT_EQ(around.last_row, 99);
  // A sphere to the side, out of view: no tile.
  const TileRange none = live_tiles(basis, glm::dvec3(-30, 0, 10), 1.0, 4, 4);
  EXPECT_GT(none.first_column, none.last_column);
  EXPECT_GT(none.first_row, none.last_row);
}

}  // namespace
}  // namespace clmarch

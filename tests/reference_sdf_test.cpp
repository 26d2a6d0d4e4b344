// The reference distance field against closed forms: each primitive and operator at chosen points,
// transforms, the color rules, and every node kind of the list.
#include "reference/reference_sdf.hpp"
#include "support/test_support.hpp"
#include "support/tolerances.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace clmarch {
namespace {

using testing::kExact;
using testing::leaf;
// 90-degree rotations go through cos(pi/2) ~ 6e-17 and a matrix product.
constexpr double kRotated = 1e-12;

const glm::dvec3 kWhite(1.0), kRed(1.0, 0.0, 0.0), kBlue(0.0, 0.0, 1.0);

Node sphere_node(glm::dvec3 center, double radius, std::optional<glm::dvec3> color = std::nullopt) {
  Node n = leaf(Sphere{center, radius}, NodeKind::Sphere);
  n.color = color;
  return n;
}

Node op_node(NodeKind kind, std::vector<Node> children, double k = 0.0) {
  Node n = node_of_kind(kind);
  n.children = std::move(children);
  std::visit(
      [k](auto& params) {
        if constexpr (requires { params.k; }) params.k = k;
      },
      n.params);
  return n;
}

void expect_color(const glm::dvec3& got, const glm::dvec3& want) {
  EXPECT_NEAR(got.r, want.r, kExact);
  EXPECT_NEAR(got.g, want.g, kExact);
  EXPECT_NEAR(got.b, want.b, kExact);
}

TEST(ReferenceSdf, Sphere) {
  const Sphere s{{1.0, 2.0, 3.0}, 2.0};
  EXPECT_NEAR(sd_sphere({1.0, 2.0, 8.0}, s), 3.0, kExact);
  EXPECT_NEAR(sd_sphere({1.0, 2.0, 3.0}, s), -2.0, kExact);
  EXPECT_NEAR(sd_sphere({1.0 + 2.0 / std::sqrt(3.0), 2.0 + 2.0 / std::sqrt(3.0), 3.0 + 2.0 / std::sqrt(3.0)}, s), 0.0,
              kExact);
  EXPECT_NEAR(sd_sphere({1.0, 2.5, 3.0}, s), -1.5, kExact);
}

TEST(ReferenceSdf, Box) {
  const Box b{{0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}};
  EXPECT_NEAR(sd_box({3.0, 0.0, 0.0}, b), 2.0, kExact);                   // face region
  EXPECT_NEAR(sd_box({0.0, -5.0, 1.0}, b), 3.0, kExact);                  // face region, negative side
  EXPECT_NEAR(sd_box({3.0, 4.0, 0.0}, b), 2.0 * std::sqrt(2.0), kExact);  // edge region
  EXPECT_NEAR(sd_box({2.0, 3.0, 4.0}, b), std::sqrt(3.0), kExact);        // corner region
  EXPECT_NEAR(sd_box({0.5, 0.0, 0.0}, b), -0.5, kExact);                  // inside, nearest face x
  EXPECT_NEAR(sd_box({0.0, 1.5, 2.8}, b), -0.2, kExact);                  // inside, nearest face z
  EXPECT_NEAR(sd_box({10.0, 10.0, 10.0}, Box{{10.0, 10.0, 10.0}, glm::dvec3(0.5)}), -0.5, kExact);
}

TEST(ReferenceSdf, RoundBox) {
  // half_size includes the rounding: the flat faces stay at 1, corners are spheres of 0.25 at 0.75.
  const RoundBox b{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 0.25};
  EXPECT_NEAR(sd_round_box({2.0, 0.0, 0.0}, b), 1.0, kExact);
  EXPECT_NEAR(sd_round_box({0.0, 0.0, 0.0}, b), -1.0, kExact);
  EXPECT_NEAR(sd_round_box({2.0, 2.0, 0.0}, b), 1.25 * std::sqrt(2.0) - 0.25, kExact);
  EXPECT_NEAR(sd_round_box({2.0, 2.0, 2.0}, b), 1.25 * std::sqrt(3.0) - 0.25, kExact);
  EXPECT_NEAR(sd_round_box(glm::dvec3(0.75 + 0.25 / std::sqrt(3.0)), b), 0.0, kExact);
}

TEST(ReferenceSdf, BoxFrame) {
  // Bars 2e = 0.2 wide, flush with the faces of the unit box: they span |x| in [0.8, 1].
  const BoxFrame f{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 0.1};
  EXPECT_NEAR(sd_box_frame({2.0, 2.0, 2.0}, f), std::sqrt(3.0), kExact);  // off the corner
  EXPECT_NEAR(sd_box_frame({0.0, 2.0, 2.0}, f), std::sqrt(2.0), kExact);
  EXPECT_NEAR(sd_box_frame({0.0, 0.0, 1.0}, f), 0.8, kExact);                   // centre of a face: hollow
  EXPECT_NEAR(sd_box_frame({0.0, 0.0, 0.0}, f), 0.8 * std::sqrt(2.0), kExact);  // centre of the box
  // Inside one bar of each family (along x, y, z), and off an edge of each family.
  EXPECT_NEAR(sd_box_frame({0.0, 0.9, 0.9}, f), -0.1, kExact);
  EXPECT_NEAR(sd_box_frame({-0.9, 0.3, 0.9}, f), -0.1, kExact);
  EXPECT_NEAR(sd_box_frame({0.9, -0.9, -0.5}, f), -0.1, kExact);
  EXPECT_NEAR(sd_box_frame({0.0, 0.95, 0.9}, f), -0.05, kExact);
  EXPECT_NEAR(sd_box_frame({-2.0, 0.5, 2.0}, f), std::sqrt(2.0), kExact);
  EXPECT_NEAR(sd_box_frame({2.0, -2.0, 0.1}, f), std::sqrt(2.0), kExact);
}

TEST(ReferenceSdf, Torus) {
  const Torus t{{0.0, 0.0, 0.0}, 1.0, 0.25};
  EXPECT_NEAR(sd_torus({0.0, 0.0, 0.0}, t), 0.75, kExact);                   // centre of the hole
  EXPECT_NEAR(sd_torus({0.0, 2.0, 0.0}, t), std::sqrt(5.0) - 0.25, kExact);  // on the axis
  EXPECT_NEAR(sd_torus({2.0, 0.0, 0.0}, t), 0.75, kExact);                   // in plane, outside
  EXPECT_NEAR(sd_torus({0.0, 0.0, -1.0}, t), -0.25, kExact);                 // on the core circle
  EXPECT_NEAR(sd_torus({0.6, 0.0, 0.8}, t), -0.25, kExact);
  EXPECT_NEAR(sd_torus({0.0, 1.0, 1.0}, t), 0.75, kExact);  // above the core
  EXPECT_NEAR(sd_torus({3.0, 1.0, -2.0}, Torus{{3.0, 1.0, 0.0}, 2.0, 0.5}), -0.5, kExact);
}

TEST(ReferenceSdf, Plane) {
  EXPECT_NEAR(sd_plane({3.0, 4.0, 5.0}, Plane{{0.0, 1.0, 0.0}, -1.0}), 3.0, kExact);
  EXPECT_NEAR(sd_plane({3.0, -4.0, 5.0}, Plane{{0.0, 1.0, 0.0}, -1.0}), -5.0, kExact);
  const Plane tilted{glm::normalize(glm::dvec3(1.0, 1.0, 0.0)), 0.5};
  EXPECT_NEAR(sd_plane({1.0, 1.0, 7.0}, tilted), std::sqrt(2.0) + 0.5, kExact);
}

TEST(ReferenceSdf, InfiniteCylinder) {
  const InfiniteCylinder c{{1.0, 0.0, 2.0}, 0.5};
  EXPECT_NEAR(sd_infinite_cylinder({1.0, 7.0, 2.0}, c), -0.5, kExact);  // on the axis, any height
  EXPECT_NEAR(sd_infinite_cylinder({4.0, -3.0, 2.0}, c), 2.5, kExact);  // beside it along x
  EXPECT_NEAR(sd_infinite_cylinder({-2.0, 1e6, 2.0}, c), 2.5, kExact);  // no caps
  EXPECT_NEAR(sd_infinite_cylinder({4.0, 0.0, 6.0}, c), 4.5, kExact);   // 3-4-5 off the axis
}

TEST(ReferenceSdf, Capsule) {
  const Capsule c{{0.0, -0.5, 0.0}, {0.0, 0.5, 0.0}, 0.25};
  EXPECT_NEAR(sd_capsule({0.0, 1.5, 0.0}, c), 0.75, kExact);   // beyond b
  EXPECT_NEAR(sd_capsule({0.0, -1.5, 0.0}, c), 0.75, kExact);  // beyond a
  EXPECT_NEAR(sd_capsule({1.0, 0.0, 0.0}, c), 0.75, kExact);   // middle
  EXPECT_NEAR(sd_capsule({0.0, 0.3, -2.0}, c), 1.75, kExact);  // beside the segment
  EXPECT_NEAR(sd_capsule({1.0, 1.5, 0.0}, c), std::sqrt(2.0) - 0.25, kExact);
  EXPECT_NEAR(sd_capsule({0.0, 0.5, 0.0}, c), -0.25, kExact);
  const Capsule slanted{{1.0, 1.0, 1.0}, {3.0, 1.0, 1.0}, 0.5};
  EXPECT_NEAR(sd_capsule({2.0, 4.0, 5.0}, slanted), 4.5, kExact);
}

TEST(ReferenceSdf, Cylinder) {
  const Cylinder c{{0.0, 0.0, 0.0}, 0.5, 0.5};
  EXPECT_NEAR(sd_cylinder({1.0, 0.0, 0.0}, c), 0.5, kExact);                   // side
  EXPECT_NEAR(sd_cylinder({0.6, 0.2, 0.8}, c), 0.5, kExact);                   // side, off axis
  EXPECT_NEAR(sd_cylinder({0.0, 1.0, 0.0}, c), 0.5, kExact);                   // cap
  EXPECT_NEAR(sd_cylinder({0.3, -2.0, 0.0}, c), 1.5, kExact);                  // bottom cap
  EXPECT_NEAR(sd_cylinder({1.0, 1.0, 0.0}, c), 0.5 * std::sqrt(2.0), kExact);  // rim edge
  EXPECT_NEAR(sd_cylinder({0.0, 0.0, 0.0}, c), -0.5, kExact);
  EXPECT_NEAR(sd_cylinder({0.4, 0.0, 0.0}, c), -0.1, kExact);
  EXPECT_NEAR(sd_cylinder({0.0, 0.45, 0.0}, c), -0.05, kExact);
  EXPECT_NEAR(sd_cylinder({1.0, 2.0, 3.5}, Cylinder{{1.0, 2.0, 3.0}, 1.0, 2.0}), -0.5, kExact);
}

TEST(ReferenceSdf, HardOperators) {
  EXPECT_EQ(op_union(0.5, -0.25), -0.25);
  EXPECT_EQ(op_intersection(0.5, -0.25), 0.5);
  EXPECT_EQ(op_subtraction(0.5, -0.25), 0.5);    // max(0.5, 0.25)
  EXPECT_EQ(op_subtraction(-0.5, 0.25), -0.25);  // max(-0.5, -0.25)
  EXPECT_EQ(op_subtraction(-0.5, -0.25), 0.25);  // b carves a
}

// The polynomial smooth min/max in Quilez's other closed form: min - max(k - |a-b|, 0)^2 / (4k).
double smin_closed(double a, double b, double k) {
  return std::min(a, b) - std::pow(std::max(k - std::abs(a - b), 0.0), 2) / (4.0 * k);
}
double smax_closed(double a, double b, double k) {
  return std::max(a, b) + std::pow(std::max(k - std::abs(a - b), 0.0), 2) / (4.0 * k);
}

TEST(ReferenceSdf, SmoothOperatorsMatchTheirClosedForms) {
  for (double k : {0.05, 0.3, 1.0}) {
    for (double a = -1.0; a <= 1.0; a += 0.0625) {
      for (double b = -1.0; b <= 1.0; b += 0.0625) {
        EXPECT_NEAR(op_smooth_union(a, b, k), smin_closed(a, b, k), kExact) << a << " " << b << " " << k;
        EXPECT_NEAR(op_smooth_intersection(a, b, k), smax_closed(a, b, k), kExact) << a << " " << b << " " << k;
        EXPECT_NEAR(op_smooth_subtraction(a, b, k), smax_closed(a, -b, k), kExact) << a << " " << b << " " << k;
        if (std::abs(a - b) >= k) {
          EXPECT_EQ(op_smooth_union(a, b, k), op_union(a, b));
          EXPECT_EQ(op_smooth_intersection(a, b, k), op_intersection(a, b));
        }
        if (std::abs(a + b) >= k) {
          EXPECT_EQ(op_smooth_subtraction(a, b, k), op_subtraction(a, b));
        }
      }
    }
    EXPECT_NEAR(op_smooth_union(0.3, 0.3, k), 0.3 - k / 4.0, kExact);
    EXPECT_NEAR(op_smooth_intersection(0.3, 0.3, k), 0.3 + k / 4.0, kExact);
    EXPECT_NEAR(op_smooth_subtraction(0.3, -0.3, k), 0.3 + k / 4.0, kExact);
  }
}

TEST(ReferenceSdf, ColorsOfHardOperators) {
  const SdfSample red{0.5, kRed}, blue{-0.25, kBlue}, red_tie{-0.25, kRed};
  expect_color(op_union(red, blue).color, kBlue);
  expect_color(op_union(red_tie, blue).color, kRed);  // tie: the first
  expect_color(op_union(blue, red_tie).color, kBlue);
  expect_color(op_intersection(red, blue).color, kRed);
  expect_color(op_intersection(blue, red_tie).color, kBlue);  // tie: the first
  expect_color(op_subtraction(red, blue).color, kRed);        // a = 0.5 >= -b = 0.25
  expect_color(op_subtraction(SdfSample{-0.5, kRed}, SdfSample{0.25, kBlue}).color, kBlue);
  expect_color(op_subtraction(SdfSample{-0.25, kRed}, SdfSample{0.25, kBlue}).color, kRed);  // a == -b
}

TEST(ReferenceSdf, ColorsOfSmoothOperators) {
  const double k = 0.5;
  const SdfSample a{0.0, kRed}, b{0.25, kBlue};
  // h = 0.75 for union (a nearer), 0.25 for intersection.
  expect_color(op_smooth_union(a, b, k).color, {0.75, 0.0, 0.25});
  expect_color(op_smooth_intersection(a, b, k).color, {0.25, 0.0, 0.75});
  // Subtraction: h = 0.5 - 0.5 * (a + b) / k = 0.25 towards b's color.
  expect_color(op_smooth_subtraction(a, b, k).color, {0.75, 0.0, 0.25});
  // Far apart, the smooth rules pick the same operand as the hard ones.
  expect_color(op_smooth_union(SdfSample{2.0, kRed}, b, k).color, kBlue);
  expect_color(op_smooth_intersection(SdfSample{2.0, kRed}, b, k).color, kRed);
  expect_color(op_smooth_subtraction(SdfSample{2.0, kRed}, b, k).color, kRed);
  expect_color(op_smooth_subtraction(SdfSample{-2.0, kRed}, b, k).color, kBlue);
}

TEST(ReferenceSdf, ColorInheritance) {
  // White by default; a leaf without color takes its nearest ancestor's; its own color wins.
  Node plain = sphere_node({0.0, 0.0, 0.0}, 1.0);
  expect_color(reference_sample(plain, {0.0, 0.0, 0.0}).color, kWhite);

  Node inner = op_node(NodeKind::Union, {sphere_node({-2.0, 0.0, 0.0}, 1.0), sphere_node({2.0, 0.0, 0.0}, 1.0, kBlue)});
  Node root = op_node(NodeKind::Union, {inner, sphere_node({0.0, 5.0, 0.0}, 1.0)});
  root.color = kRed;
  expect_color(reference_sample(root, {-2.0, 0.0, 0.0}).color, kRed);
  expect_color(reference_sample(root, {2.0, 0.0, 0.0}).color, kBlue);
  expect_color(reference_sample(root, {0.0, 5.0, 0.0}).color, kRed);
  root.children[0].color = glm::dvec3(0.0, 1.0, 0.0);
  expect_color(reference_sample(root, {-2.0, 0.0, 0.0}).color, {0.0, 1.0, 0.0});
  expect_color(reference_sample(root, {0.0, 5.0, 0.0}).color, kRed);
}

TEST(ReferenceSdf, OperatorNodesFoldLeft) {
  const Node a = sphere_node({0.0, 0.0, 0.0}, 1.0), b = sphere_node({1.5, 0.0, 0.0}, 1.0),
             c = sphere_node({0.0, 1.5, 0.0}, 1.0);
  for (const glm::dvec3 p : {glm::dvec3(0.2, 0.3, 0.1), glm::dvec3(1.0, 1.0, 0.5), glm::dvec3(-2.0, 0.5, 1.0)}) {
    const double da = sd_sphere(p, {{0.0, 0.0, 0.0}, 1.0}), db = sd_sphere(p, {{1.5, 0.0, 0.0}, 1.0}),
                 dc = sd_sphere(p, {{0.0, 1.5, 0.0}, 1.0});
    const double k = 0.4;
    EXPECT_NEAR(reference_distance(op_node(NodeKind::Union, {a, b, c}), p), std::min({da, db, dc}), kExact);
    EXPECT_NEAR(reference_distance(op_node(NodeKind::Intersection, {a, b, c}), p), std::max({da, db, dc}), kExact);
    EXPECT_NEAR(reference_distance(op_node(NodeKind::Subtraction, {a, b, c}), p), std::max({da, -db, -dc}), kExact);
    EXPECT_NEAR(reference_distance(op_node(NodeKind::SmoothUnion, {a, b, c}, k), p),
                op_smooth_union(op_smooth_union(da, db, k), dc, k), kExact);
    EXPECT_NEAR(reference_distance(op_node(NodeKind::SmoothIntersection, {a, b, c}, k), p),
                op_smooth_intersection(op_smooth_intersection(da, db, k), dc, k), kExact);
    EXPECT_NEAR(reference_distance(op_node(NodeKind::SmoothSubtraction, {a, b, c}, k), p),
                op_smooth_subtraction(op_smooth_subtraction(da, db, k), dc, k), kExact);
    EXPECT_NEAR(reference_distance(op_node(NodeKind::Subtraction, {a}), p), da, kExact);
  }
}

TEST(ReferenceSdf, Translate) {
  Node n = sphere_node({1.0, 0.0, 0.0}, 0.5);
  n.transform.translate = {0.0, 2.0, 0.0};
  EXPECT_NEAR(reference_distance(n, {1.0, 2.0, 0.0}), -0.5, kExact);
  EXPECT_NEAR(reference_distance(n, {1.0, 2.0, 3.0}), 2.5, kExact);
}

// An off-centre sphere shows where each rotation sends the local axes (right-handed, degrees).
TEST(ReferenceSdf, RotateNinetyDegreesAboutEachAxis) {
  struct Case {
    glm::dvec3 rotate, local_center, world_center;
  };
  const Case cases[] = {
      {{90.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}},   // x: y -> z
      {{0.0, 90.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, -1.0}},  // y: x -> -z
      {{0.0, 0.0, 90.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}},   // z: x -> y
      {{90.0, 90.0, 0.0}, {0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}},  // x first, then y: y -> z -> x
  };
  for (const Case& c : cases) {
    Node n = sphere_node(c.local_center, 0.5);
    n.transform.rotate_degrees = c.rotate;
    EXPECT_NEAR(reference_distance(n, c.world_center), -0.5, kRotated) << c.rotate.x << c.rotate.y << c.rotate.z;
    EXPECT_NEAR(reference_distance(n, c.local_center), std::sqrt(2.0) - 0.5, kRotated);
  }
  // A box of unequal sides: rotating 90 degrees about x swaps its y and z extents.
  Node box = leaf(Box{{0.0, 0.0, 0.0}, {0.1, 0.2, 0.3}}, NodeKind::Box);
  box.transform.rotate_degrees = {90.0, 0.0, 0.0};
  EXPECT_NEAR(reference_distance(box, {0.0, 1.0, 0.0}), 0.7, kRotated);
  EXPECT_NEAR(reference_distance(box, {0.0, 0.0, 1.0}), 0.8, kRotated);
}

TEST(ReferenceSdf, UniformScaleMultipliesDistance) {
  Node n = leaf(Box{{0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}}, NodeKind::Box);
  n.transform.scale = 2.0;
  EXPECT_NEAR(reference_distance(n, {6.0, 0.0, 0.0}), 4.0, kExact);  // face at x = 2
  EXPECT_NEAR(reference_distance(n, {0.0, 0.0, 0.0}), -2.0, kExact);
  n.transform.translate = {1.0, 1.0, 1.0};
  EXPECT_NEAR(reference_distance(n, {1.0, 1.0, 10.0}), 3.0, kExact);  // face at z = 1 + 6
}

TEST(ReferenceSdf, TransformAppliesToTheSubtree) {
  Node u = op_node(NodeKind::Union, {sphere_node({1.0, 0.0, 0.0}, 0.5), sphere_node({-1.0, 0.0, 0.0}, 0.5)});
  u.transform.translate = {0.0, 0.0, 5.0};
  u.transform.rotate_degrees = {0.0, 0.0, 90.0};
  u.transform.scale = 2.0;
  // Children end up at (0, +-2, 5) with radius 1.
  EXPECT_NEAR(reference_distance(u, {0.0, 2.0, 5.0}), -1.0, kRotated);
  EXPECT_NEAR(reference_distance(u, {0.0, -2.0, 5.0}), -1.0, kRotated);
  EXPECT_NEAR(reference_distance(u, {3.0, 2.0, 5.0}), 2.0, kRotated);
  // A nested transform composes: the child's translate is in the parent's local frame.
  u.children[0].transform.translate = {0.0, 1.0, 0.0};
  EXPECT_NEAR(reference_distance(u, {-2.0, 2.0, 5.0}), -1.0, kRotated);
}

TEST(ReferenceSdf, MalformedTreesThrow) {
  Node mismatched = leaf(Sphere{}, NodeKind::Box);
  EXPECT_THROW(reference_distance(mismatched, glm::dvec3(0.0)), std::invalid_argument);
  EXPECT_THROW(reference_distance(op_node(NodeKind::Union, {}), glm::dvec3(0.0)), std::invalid_argument);
  EXPECT_THROW(
      reference_distance(op_node(NodeKind::SmoothUnion, {sphere_node(glm::dvec3(0.0), 1.0)}, 0.0), glm::dvec3(0.0)),
      std::invalid_argument);
}

// The step factor that makes a default primitive 1-Lipschitz, for the check below. A value-noise
// terrain's height has slope at most amplitude * frequency * octaves * 1.5 sqrt(2) (value noise
// changes by at most 1.5 per lattice unit along each axis; octave i has weight 0.5^i at frequency
// 2^i), so p.y - height has slope at most 1 + that. The Mandelbulb's escape-time estimate is no
// proven bound: its slope was measured up to 1.62 over 2e5 pairs in [-2, 2]^3 (steepest where
// the escaping iteration changes), so it gets 0.5.
double unit_slope_step_factor(const NodeParams& params) {
  if (const Terrain* t = std::get_if<Terrain>(&params)) {
    EXPECT_EQ(t->noise, TerrainNoise::Value);
    return 1.0 / (1.0 + t->amplitude * t->frequency * t->octaves * 1.5 * std::sqrt(2.0));
  }
  if (std::holds_alternative<Mandelbulb>(params)) return 0.5;
  return 1.0;
}

Node default_node(NodeKind kind) {
  if (is_primitive(kind)) {
    Node node = node_of_kind(kind);
    node.step_factor = unit_slope_step_factor(node.params);
    return node;
  }
  if (kind == NodeKind::Repeat) {
    // One child that fits its repetition cell, so the field stays continuous and 1-Lipschitz.
    Node node = op_node(kind, {sphere_node({0.0, 0.0, 0.0}, 0.5)});
    node.params = Repeat{{2.0, 0.0, 2.0}};
    return node;
  }
  if (kind == NodeKind::Displace) {
    Node node = op_node(kind, {sphere_node({0.0, 0.0, 0.0}, 0.5)});
    node.params = Displace{0.1, 2.0};
    return node;
  }
  if (is_blend_operator(kind)) {
    // Radius 0.2, steps 2, ra and rb 0.1; an estimate's step factor 1 / sqrt 2 makes it a bound.
    Node node = op_node(kind, {sphere_node({0.0, 0.0, 0.0}, 0.5), sphere_node({0.3, 0.2, 0.0}, 0.6, kRed)});
    std::visit(
        [](auto& params) {
          for_each_param(params, [](const ParamSpec& spec, auto& value) {
            using Value = std::decay_t<decltype(value)>;
            if constexpr (std::is_same_v<Value, int>) value = 2;
            if constexpr (std::is_same_v<Value, double>) value = std::string(spec.key) == "radius" ? 0.2 : 0.1;
          });
        },
        node.params);
    node.step_factor = 1.0 / operator_lipschitz(node);
    return node;
  }
  // The operators of one child, each with parameters that keep the field continuous: the copies
  // of the repetitions fit their sectors and cells.
  const auto unary = [&](NodeParams params, Node child) {
    Node node = op_node(kind, {std::move(child)});
    node.params = std::move(params);
    return node;
  };
  const Node box_child = leaf(Box{{0.2, 0.1, 0.0}, {0.5, 0.3, 0.4}}, NodeKind::Box);
  switch (kind) {
    case NodeKind::Elongate:
      return unary(Elongate{{0.3, 0.0, 0.2}}, box_child);
    case NodeKind::Onion:
      return unary(Onion{0.1}, box_child);
    case NodeKind::Round:
      return unary(Round{0.2}, box_child);
    case NodeKind::Mirror:
      return unary(Mirror{{true, false, true}}, sphere_node({0.7, 0.2, 0.5}, 0.4));
    case NodeKind::RepeatPolar:
      return unary(RepeatPolar{6}, sphere_node({1.0, 0.1, 0.0}, 0.3));
    case NodeKind::RepeatLimited:
      return unary(RepeatLimited{{1.5, 0.0, 1.5}, {-1, 0, -1}, {1, 0, 1}}, sphere_node({0.0, 0.0, 0.0}, 0.5));
    case NodeKind::Revolve:
      return unary(Revolve{0.5}, leaf(Circle{{0.3, 0.1, 0.0}, 0.3}, NodeKind::Circle));
    case NodeKind::Extrude:
      return unary(Extrude{0.4}, leaf(Rectangle{{0.1, 0.0, 0.0}, 0.5, 0.3}, NodeKind::Rectangle));
    case NodeKind::Twist:
      return unary(Twist{60.0}, box_child);
    case NodeKind::Bend:
      return unary(Bend{-40.0}, box_child);
    case NodeKind::NonuniformScale:
      return unary(NonuniformScale{{1.5, 0.7, 1.0}}, box_child);
    default:
      break;
  }
  Node other = sphere_node({0.3, 0.2, 0.0}, 0.6, kRed);
  return op_node(kind, {sphere_node({0.0, 0.0, 0.0}, 0.5), other}, is_smooth_operator(kind) ? 0.25 : 0.0);
}

// Every kind of the list gives a finite distance and color, and is 1-Lipschitz, as exact distances
// and their (smooth) min/max are (steeper bounds after their step factor, see above). A kind added
// to the list but not to the reference fails here.
TEST(ReferenceSdf, EveryNodeKindIsEvaluated) {
  // Rounding of O(1) values across a few operations.
  constexpr double kLipschitzSlack = 1e-12;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  for (NodeKind kind : kAllNodeKinds) {
    SCOPED_TRACE(std::string(node_kind_name(kind)));
    const Node node = default_node(kind);
    for (int i = 0; i < 200; ++i) {
      const glm::dvec3 p(coord(rng), coord(rng), coord(rng));
      const glm::dvec3 q = p + 0.1 * glm::dvec3(coord(rng), coord(rng), coord(rng));
      SdfSample s;
      ASSERT_NO_THROW(s = reference_sample(node, p));
      ASSERT_TRUE(std::isfinite(s.distance));
      ASSERT_TRUE(std::isfinite(s.color.r) && std::isfinite(s.color.g) && std::isfinite(s.color.b));
      const double at_q = reference_distance(node, q);
      // Quilez's ellipsoid is a bound only outside (slope measured at most 0.99984 there over 1e7
      // pairs); inside, its value jumps with the direction at the centre.
      if (kind == NodeKind::Ellipsoid && (s.distance < 0.0 || at_q < 0.0)) continue;
      EXPECT_LE(std::abs(at_q - s.distance), glm::length(q - p) + kLipschitzSlack);
    }
  }
}

}  // namespace
}  // namespace clmarch

// The blend operators (node_kinds.def's CLMARCH_BLEND) over every kind of the list: the reference's
// field is as steep as operator_lipschitz says and no steeper, and the kernel picks the material
// and the id of the operand the reference picks.
#include "reference/reference_sdf.hpp"
#include "scene/scene_bounds.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {
namespace {

std::vector<NodeKind> blend_kinds() {
  std::vector<NodeKind> kinds;
  for (NodeKind kind : kAllNodeKinds) {
    if (is_blend_operator(kind)) kinds.push_back(kind);
  }
  return kinds;
}

/// The blend's parameters as a flow map's entries: radius 0.5, steps 3, ra 0.3, rb 0.2.
std::string parameters(NodeKind kind) {
  std::string entries;
  for (const ParamSpec& spec : param_table(kind)) {
    const std::string key = spec.key;
    const char* value = key == "steps" ? "3" : key == "ra" ? "0.3" : key == "rb" ? "0.2" : "0.5";
    entries += key + ": " + value + ", ";
  }
  return entries;
}

/// Two overlapping spheres, red and blue, and with three a green one: every blend region is near.
Scene blend_scene(NodeKind kind, int children) {
  std::string list =
      "[{sphere: {center: [-0.5, 0, 0], radius: 1, color: [1, 0, 0]}}, "
      "{sphere: {center: [0.7, 0.2, 0], radius: 0.8, color: [0, 0, 1]}}";
  if (children == 3) list += ", {sphere: {center: [0, 0.9, 0.3], radius: 0.6, color: [0, 1, 0]}}";
  list += "]";
  return testing::scene_from_yaml("sdf:\n  " + std::string(node_kind_name(kind)) + ": {" + parameters(kind) +
                                  "children: " + list + "}\n");
}

class BlendOperator : public ::testing::TestWithParam<NodeKind> {};

// |d(p) - d(q)| <= L |p - q| for L = operator_lipschitz: 1 for the bounds, sqrt(children) for the
// estimates, which must also be seen steeper than 1 (else they would be bounds, and the docs wrong).
TEST_P(BlendOperator, ReferenceIsAsSteepAsItsLipschitzConstant) {
  const NodeKind kind = GetParam();
  std::mt19937 random(13);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0), offset(-0.3, 0.3);
  double steepest = 0.0, lipschitz = 1.0;
  for (int children : {2, 3}) {
    const Scene scene = blend_scene(kind, children);
    lipschitz = operator_lipschitz(scene.sdf);
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec3 p(coordinate(random), coordinate(random), coordinate(random));
      const glm::dvec3 q = p + glm::dvec3(offset(random), offset(random), offset(random));
      const double moved = glm::length(q - p);
      const double change = std::abs(reference_distance(scene.sdf, p) - reference_distance(scene.sdf, q));
      steepest = std::max(steepest, change / moved);
      ASSERT_LE(change, lipschitz * moved * (1.0 + 1e-9) + 1e-12)
          << node_kind_name(kind) << " with " << children << " children from (" << p.x << ", " << p.y << ", " << p.z
          << ") to (" << q.x << ", " << q.y << ", " << q.z << ")";
    }
  }
  if (lipschitz > 1.0) {
    EXPECT_GT(steepest, 1.01) << node_kind_name(kind) << " is an estimate, but was never steeper than 1";
  }
}

// The color rule of docs/scene-format.md, kernel against reference at 1 and 16 lanes; points where
// the reference's choice changes within 1e-4 are left out (float rounding may choose otherwise).
TEST_P(BlendOperator, KernelTakesTheMaterialAndIdTheReferenceTakes) {
  const NodeKind kind = GetParam();
  const Scene scene = blend_scene(kind, 3);
  std::mt19937 random(17);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  std::vector<glm::dvec3> points;
  while (points.size() < 200) {
    const glm::dvec3 p(coordinate(random), coordinate(random), coordinate(random));
    const SdfSample here = reference_sample(scene.sdf, p);
    bool steady = true;
    for (int axis = 0; axis < 3; ++axis) {
      for (double step : {-1e-4, 1e-4}) {
        glm::dvec3 near = p;
        near[axis] += step;
        if (reference_sample(scene.sdf, near).primitive != here.primitive) steady = false;
      }
    }
    if (steady) points.push_back(p);
  }
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    const PointSamples samples = eval_points_opencl(scene, points, options);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const SdfSample expected = reference_sample(scene.sdf, points[i]);
      EXPECT_NEAR(samples.distance[i], expected.distance, 2e-5)
          << node_kind_name(kind) << " lanes " << lanes << " point " << i;
      EXPECT_EQ(samples.primitive[i], static_cast<float>(expected.primitive))
          << node_kind_name(kind) << " lanes " << lanes << " point " << i;
      EXPECT_NEAR(samples.albedo[i].x, expected.color.x, 1e-6) << node_kind_name(kind) << " point " << i;
      EXPECT_NEAR(samples.albedo[i].y, expected.color.y, 1e-6) << node_kind_name(kind) << " point " << i;
      EXPECT_NEAR(samples.albedo[i].z, expected.color.z, 1e-6) << node_kind_name(kind) << " point " << i;
    }
  }
}

// The union blends' growth of the bounding sphere is reached: two coincident unit spheres (a = b
// everywhere) blend into a sphere whose radius is 1 + the growth, found here along a ray of the
// reference's field, and the bound is exactly that sphere (scene/scene_bounds.cpp's derivation).
TEST(BlendBounds, UnionBlendsOfCoincidentSpheresReachTheirGrowth) {
  const std::string spheres = "children: [{sphere: {radius: 1}}, {sphere: {radius: 1}}]}";
  const std::pair<std::string, double> cases[] = {
      {"union_chamfer: {radius: 0.4, ", 1.2},
      {"union_round: {radius: 0.4, ", 1.0 + 0.4 * (1.0 - std::sqrt(0.5))},
      {"union_stairs: {radius: 0.4, steps: 3, ", 1.2},  // the middle step's corner on a = b
      {"union_columns: {radius: 0.4, steps: 1, ", 1.2},
      {"xor: {", 1.0}};
  for (const auto& [head, surface] : cases) {
    const Node node = testing::scene_from_yaml("sdf:\n  " + head + spheres + "\n").sdf;
    // The sign changes at the surface along the ray x > 0: bisect for it.
    double inside = 0.5, outside = 3.0;
    for (int i = 0; i < 100; ++i) {
      const double middle = 0.5 * (inside + outside);
      (reference_distance(node, {middle, 0.0, 0.0}) < 0.0 ? inside : outside) = middle;
    }
    // xor(a, a) = |a| has no inside; its bound is the spheres'.
    if (head != "xor: {") {
      EXPECT_NEAR(inside, surface, 1e-9) << head;
    }
    EXPECT_NEAR(node_bounds(node)->radius, surface, 1e-12) << head;
  }
}

// docs/scene-format.md's colour rules at points where the answer is plain: red a and blue b are the
// half spaces x <= 0 and y <= 0 (b: y >= 0 for the differences, x <= 0 for the cutting tools, whose
// a is y <= 0), or for xor two spheres.
TEST(BlendColors, FollowTheDocumentedRules) {
  const auto color_at = [](const std::string& head, const char* a, const char* b, const glm::dvec3& p) {
    const Node node =
        testing::scene_from_yaml(fmt::format("sdf:\n  {}children: [{{plane: {{normal: {}, color: [1, 0, 0]}}}}, "
                                             "{{plane: {{normal: {}, color: [0, 0, 1]}}}}]}}\n",
                                             head, a, b))
            .sdf;
    return reference_sample(node, p).color;
  };
  const glm::dvec3 red(1, 0, 0), blue(0, 0, 1);
  const char* x = "[1, 0, 0]";
  const char* y = "[0, 1, 0]";
  const char* minus_y = "[0, -1, 0]";
  // Unions: the nearer operand, also in the fillet; intersections: the farther.
  EXPECT_EQ(color_at("union_round: {radius: 1, ", x, y, {0.2, 0.5, 0}), red);
  EXPECT_EQ(color_at("union_round: {radius: 1, ", x, y, {0.5, 0.2, 0}), blue);
  EXPECT_EQ(color_at("union_stairs: {radius: 1, steps: 2, ", x, y, {0.6, 0.3, 0}), blue);
  EXPECT_EQ(color_at("intersection_chamfer: {radius: 1, ", x, y, {-0.2, -0.5, 0}), red);
  EXPECT_EQ(color_at("intersection_columns: {radius: 1, steps: 2, ", x, y, {-0.5, -0.2, 0}), blue);
  // Differences: the carved surface takes b's colour.
  EXPECT_EQ(color_at("difference_chamfer: {radius: 1, ", x, minus_y, {-0.5, -0.2, 0}), blue);
  EXPECT_EQ(color_at("difference_round: {radius: 1, ", x, minus_y, {-0.2, -0.5, 0}), red);
  // Cutting tools: b's colour where the cut or the tongue changes a.
  EXPECT_EQ(color_at("engrave: {radius: 0.5, ", y, x, {0, 0.1, 0}), blue);
  EXPECT_EQ(color_at("engrave: {radius: 0.5, ", y, x, {2, 0.1, 0}), red);
  EXPECT_EQ(color_at("groove: {ra: 0.5, rb: 0.25, ", y, x, {0, 0.1, 0}), blue);
  EXPECT_EQ(color_at("tongue: {ra: 0.5, rb: 0.25, ", y, x, {0, 0.3, 0}), blue);
  EXPECT_EQ(color_at("tongue: {ra: 0.5, rb: 0.25, ", y, x, {2, 0.3, 0}), red);
  // Pipe: the operand of the smaller |distance|.
  EXPECT_EQ(color_at("pipe: {radius: 0.1, ", x, y, {0.1, -0.5, 0}), red);
  // Xor: inside both red and blue spheres, nearer blue's surface.
  const Node both = testing::scene_from_yaml(
                        "sdf:\n  xor: [{sphere: {radius: 1, color: [1, 0, 0]}}, "
                        "{sphere: {center: [1.5, 0, 0], radius: 1, color: [0, 0, 1]}}]\n")
                        .sdf;
  EXPECT_EQ(reference_sample(both, {0.7, 0, 0}).color, blue);
  EXPECT_EQ(reference_sample(both, {0.8, 0, 0}).color, red);
}

INSTANTIATE_TEST_SUITE_P(EveryBlend, BlendOperator, ::testing::ValuesIn(blend_kinds()),
                         [](const auto& info) { return std::string(node_kind_name(info.param)); });

}  // namespace
}  // namespace clmarch

// Subtree bounds in the generated map(): an expensive bounded subtree inside a union, subtraction
// or smooth union/subtraction is evaluated only when its bounding sphere says it can change the
// result. The generated code must gate exactly those subtrees, and the gated map() must still be
// the scene's field and material (checked against the CPU reference, which never skips).
#include "codegen/kernel_source.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <random>

namespace clmarch {
namespace {

using testing::scene_from_yaml;

// The comment the generator writes beside each gate's bound.
constexpr const char* kGate = "/* bound of ";

std::string map_source(const std::string& sdf_yaml) {
  return generate_kernel_source(scene_from_yaml("sdf:\n  " + sdf_yaml + "\n"), {KernelPurpose::EvalPoints, 16});
}

TEST(SubtreeBounds, ExpensiveBoundedSubtreesAreGatedCheapOnesAreNot) {
  const std::string menger_last = map_source("union: [{plane: {normal: [0, 1, 0], offset: 1.4}}, {menger: {}}]");
  EXPECT_NE(menger_last.find(kGate), std::string::npos) << menger_last;
  EXPECT_NE(menger_last.find("if (LANE_ANY("), std::string::npos);
  // A union evaluates its cheap children first even when the expensive one comes first.
  const std::string menger_first = map_source("union: [{menger: {}}, {plane: {normal: [0, 1, 0], offset: 1.4}}]");
  ASSERT_NE(menger_first.find(kGate), std::string::npos) << menger_first;
  EXPECT_LT(menger_first.find("sd_plane(p"), menger_first.find(kGate));
  // Cheap subtrees, unbounded ones and intersections are evaluated as they are.
  EXPECT_EQ(map_source("union: [{sphere: {}}, {box: {}}]").find(kGate), std::string::npos);
  EXPECT_EQ(map_source("union: [{sphere: {}}, {terrain: {}}]").find(kGate), std::string::npos);
  EXPECT_EQ(map_source("intersection: [{sphere: {}}, {menger: {}}]").find(kGate), std::string::npos);
  // A lone subtree has nothing to be compared with.
  EXPECT_EQ(map_source("mandelbulb: {}").find(kGate), std::string::npos);
  // The gates nest: a union inside a subtraction, each with its own.
  const std::string nested = map_source(
      "subtraction: [{box: {half_size: [3, 3, 3]}}, {union: [{sphere: {}}, {menger: {}}, {mandelbulb: {}}]}]");
  int gates = 0;
  for (std::size_t at = nested.find(kGate); at != std::string::npos; at = nested.find(kGate, at + 1)) ++gates;
  // The union behind the box, then the menger and the mandelbulb inside it; in map() and map_color().
  EXPECT_EQ(gates, 3 * 2) << nested;
}

TEST(SubtreeBounds, TheSettingTurnsThemOff) {
  const Scene on = scene_from_yaml("sdf: {union: [{plane: {}}, {menger: {}}]}\n");
  EXPECT_EQ(on.render.subtree_bounds, SceneBounds::Sphere);
  EXPECT_NE(generate_kernel_source(on, {KernelPurpose::Shaded, 16}).find(kGate), std::string::npos);
  const Scene off = scene_from_yaml("render: {subtree_bounds: none}\nsdf: {union: [{plane: {}}, {menger: {}}]}\n");
  EXPECT_EQ(generate_kernel_source(off, {KernelPurpose::Shaded, 16}).find(kGate), std::string::npos);
  EXPECT_EQ(testing::error_of("render: {subtree_bounds: box}\nsdf: {sphere: {}}\n"),
            "s.yaml:1:26: render.subtree_bounds must be one of none, sphere (got 'box')");
}

// Points spread over the scenes below, some near the subtrees, some far (|p| <= 6).
std::vector<glm::dvec3> spread_points() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-6.0, 6.0), near(-1.6, 1.6);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 1500; ++i) points.push_back({coord(rng), coord(rng), coord(rng)});
  for (int i = 0; i < 1500; ++i) points.push_back({near(rng), near(rng), near(rng)});
  return points;
}

TEST(SubtreeBounds, GatedFieldsAndMaterialsEqualTheReference) {
  // Float evaluation of these trees at |p| <= 6: a few ulps of the operands (Menger: one ulp per
  // level, kernel_sdf and fractal tests); the Mandelbulb's orbit as in MandelbulbKernel.
  constexpr double kFloatTolerance = 1e-4;
  std::vector<std::string> trees = {
      "union: [{menger: {color: [1, 0, 0]}}, {plane: {normal: [0, 1, 0], offset: 1.4, color: [0, 1, 0]}}]",
      "union: [{sphere: {center: [3, 0, 0], color: [0, 0, 1]}}, {menger: {half_size: 0.8, translate: [-2, 0.5, 0], "
      "rotate: [10, 20, 30], color: [1, 1, 0]}}, {mandelbulb: {scale: 0.7, step_factor: 0.8, center: [0, 0, 2]}}]",
      "subtraction: [{box: {half_size: [3, 3, 3], color: [0.2, 0.4, 0.6]}}, {menger: {translate: [2.5, 0, 0], color: "
      "[1, 0, 1]}}]",
      "smooth_union: {k: 0.5, children: [{sphere: {radius: 0.8, color: [1, 0, 0]}}, {menger: {translate: [2.2, 0, 0], "
      "color: [0, 0, 1]}}]}",
      "smooth_subtraction: {k: 0.3, children: [{box: {half_size: [2, 2, 2]}}, {mandelbulb: {translate: [0, 2, 0], "
      "color: [0, 1, 0]}}]}",
  };
  // The blends' skip limits (codegen/blend_code.cpp): a gated Menger sponge after a cheap operand.
  const std::string blend_with =
      "[{sphere: {radius: 0.8, color: [1, 0, 0]}}, {menger: {translate: [2.2, 0, 0], color: [0, 0, 1]}}]";
  const std::string cut_with =
      "[{box: {half_size: [2, 2, 2], color: [1, 0, 0]}}, {menger: {translate: [2.5, 0, 0], color: [0, 0, 1]}}]";
  for (const char* blend :
       {"union_chamfer: {radius: 0.3, ", "union_round: {radius: 0.3, ", "union_stairs: {radius: 0.3, steps: 3, ",
        "union_columns: {radius: 0.3, steps: 2, ", "xor: {"}) {
    trees.push_back(std::string(blend) + "children: " + blend_with + "}");
  }
  for (const char* blend :
       {"difference_chamfer: {radius: 0.3, ", "difference_round: {radius: 0.3, ",
        "difference_stairs: {radius: 0.3, steps: 3, ", "difference_columns: {radius: 0.3, steps: 2, ",
        "engrave: {radius: 0.2, ", "groove: {ra: 0.2, rb: 0.1, ", "tongue: {ra: 0.2, rb: 0.1, "}) {
    trees.push_back(std::string(blend) + "children: " + cut_with + "}");
  }
  const std::vector<glm::dvec3> points = spread_points();
  for (const std::string& tree : trees) {
    const Scene scene = scene_from_yaml("sdf:\n  " + tree + "\n");
    ASSERT_NE(generate_kernel_source(scene, {KernelPurpose::EvalPoints, 16}).find(kGate), std::string::npos) << tree;
    for (int lanes : {1, 16}) {
      OpenClOptions options;
      options.lanes = lanes;
      const PointSamples samples = eval_points_opencl(scene, points, options);
      int material_mismatches = 0;
      for (std::size_t i = 0; i < points.size(); ++i) {
        const SdfSample expected = reference_sample(scene.sdf, points[i]);
        ASSERT_NEAR(samples.distance[i], expected.distance, kFloatTolerance)
            << tree << " lanes " << lanes << " at " << points[i].x << " " << points[i].y << " " << points[i].z;
        EXPECT_EQ(samples.distance[i], samples.color_distance[i]);
        // Materials switch where two operands are equal: float rounding may pick the other side
        // within kFloatTolerance of such a seam, nowhere else.
        if (glm::length(glm::dvec3(samples.albedo[i]) - expected.color) > 1e-5) ++material_mismatches;
      }
      EXPECT_LE(material_mismatches, 3) << tree << " lanes " << lanes;
    }
  }
}

}  // namespace
}  // namespace clmarch

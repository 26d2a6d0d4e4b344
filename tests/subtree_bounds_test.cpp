// Subtree bounds in the generated map(): an expensive bounded subtree inside a union, subtraction
// or smooth union/subtraction is evaluated only when its bounding sphere says it can change the
// result, and a union's many cheap bounded children are grouped by place, each group behind the
// sphere holding it (prune/operand_groups.hpp). The generated code must gate exactly those, and the
// gated map() must still be the scene's field and material (checked against the CPU reference,
// which never skips, and against the ungated program's pictures, bit for bit).
#include "codegen/kernel_source.hpp"
#include "prune/operand_groups.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <random>
#include <set>

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

int count_of(const std::string& text, const std::string& what) {
  int count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// The comment a union grouped by place starts with.
constexpr const char* kGrouped = "operands of the union by place";

// A floor and 4 x 3 cheap primitives of different kinds a unit apart, each its own colour: the
// layout of the primitive galleries users port.
std::string gallery_union() {
  const char* const kinds[] = {"sphere: {radius: 0.3",
                               "box: {half_size: [0.25, 0.25, 0.25]",
                               "torus: {major_radius: 0.25, minor_radius: 0.08",
                               "capsule: {a: [0, -0.2, 0], b: [0, 0.2, 0], radius: 0.1",
                               "octahedron: {size: 0.3",
                               "cylinder: {radius: 0.2, half_height: 0.25"};
  std::string yaml = "union:\n    - plane: {normal: [0, 1, 0], offset: 0.5, color: [0.5, 0.5, 0.5]}\n";
  for (int i = 0; i < 12; ++i) {
    yaml += fmt::format("    - {}, translate: [{}, 0, {}], color: [{}, {}, 0.5]}}\n", kinds[i % 6], i % 4 - 1.5,
                        i / 4 - 1, 0.1 * (i % 4), 0.1 * (i / 4));
  }
  return yaml;
}

/// The gallery as the second child of a union.
std::string nested_gallery_union() {
  std::string nested = "union:\n    - sphere: {radius: 0.2, color: [0, 1, 1]}\n    - union:\n";
  const std::string gallery = gallery_union();
  for (std::size_t at = gallery.find('\n') + 1; at < gallery.size();) {
    const std::size_t end = gallery.find('\n', at);
    nested += "    " + gallery.substr(at, end - at + 1);
    at = end + 1;
  }
  return nested;
}

TEST(SubtreeBounds, UnionsOfManyCheapBoundedChildrenAreGroupedByPlace) {
  const std::string grouped = map_source(gallery_union());
  // In map() alone (map_color() runs once per hit); the gates' spheres hold groups, never a single
  // cheap primitive.
  EXPECT_EQ(count_of(grouped, kGrouped), 1) << grouped;
  EXPECT_GT(count_of(grouped, " operands */"), 2) << grouped;
  EXPECT_EQ(count_of(grouped, "/* bound of 1 operands */"), 0) << grouped;
  // The floor (unbounded) is evaluated before every group.
  const std::size_t groups_at = grouped.find(kGrouped);
  EXPECT_LT(grouped.find("sd_plane(p", groups_at), grouped.find(kGate, groups_at));
  // Fewer than four cheap bounded children, or nothing to gain: as before, no groups.
  EXPECT_EQ(map_source("union: [{sphere: {}}, {box: {translate: [3, 0, 0]}}, {torus: {translate: [6, 0, 0]}}]")
                .find(kGrouped),
            std::string::npos);
  // Five small boxes (a table) cost less together than a group's bound is worth.
  EXPECT_EQ(map_source("union: [{box: {half_size: [1.2, 0.05, 0.7]}}, {box: {center: [-1, -0.4, -0.5]}}, {box: "
                       "{center: [1, -0.4, -0.5]}}, {box: {center: [-1, -0.4, 0.5]}}, {box: {center: [1, -0.4, 0.5]}}]")
                .find(kGrouped),
            std::string::npos);
  const Scene off = scene_from_yaml("render: {subtree_bounds: none}\nsdf:\n  " + gallery_union());
  EXPECT_EQ(generate_kernel_source(off, {KernelPurpose::Shaded, 16}).find(kGrouped), std::string::npos);
  // render.literals: buffer keys a program by the tree's shape alone: no groups that follow positions.
  const Scene read = scene_from_yaml("render: {literals: buffer}\nsdf:\n  " + gallery_union());
  EXPECT_EQ(generate_kernel_source(read, {KernelPurpose::Shaded, 16}).find(kGrouped), std::string::npos);
}

TEST(SubtreeBounds, ANanBeforeTheGroupsSkipsNone) {
  // The one unbounded child, a glsl map that is NaN everywhere, comes first: fmin() ignores it, so
  // the union is the least of the others, grouped or not.
  const std::string gallery = gallery_union();
  const Scene scene = scene_from_yaml("sdf:\n  union:\n" + gallery.substr(gallery.find("    - sphere")) +
                                      "    - glsl: {code: 'float map(vec3 p) { return sqrt(-1.0 - p.x * p.x); }'}\n");
  ASSERT_NE(generate_kernel_source(scene, {KernelPurpose::EvalPoints, 16}).find(kGrouped), std::string::npos);
  const std::vector<glm::dvec3> points = {{-1.5, 0.8, -1}, {0.5, 0.2, 0}, {1.5, -0.1, 1}, {0, 3, 0}};
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    const PointSamples samples = eval_points_opencl(scene, points, options);
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_NEAR(samples.distance[i], reference_sample(scene.sdf, points[i]).distance, 1e-5)
          << "lanes " << lanes << " point " << i;
    }
  }
}

std::vector<GroupedOperand> operands_in_a_row(int count, int axis) {
  std::vector<GroupedOperand> operands;
  for (int i = 0; i < count; ++i) {
    BoundingSphere bounds;
    bounds.center[axis] = static_cast<double>((i * 5) % count);  // out of order along the axis
    bounds.radius = 0.1 + 0.05 * (i % 3);
    bounds.gain = i == 4 ? 1.5 : 1.0;
    operands.push_back({static_cast<std::size_t>(i), bounds, 1 + i % 3});
  }
  return operands;
}

/// Checks one group of a hierarchy and those below it; returns the operands' indices under it.
std::multiset<std::size_t> check_group(const OperandGroup& group) {
  std::multiset<std::size_t> under;
  const bool leaf = group.halves.empty();
  EXPECT_TRUE(leaf ? !group.operands.empty() && group.operands.size() <= kLeafOperands
                   : group.halves.size() == 2 && group.operands.empty());
  int cost = 0;
  double gain = 0.0;
  const auto holds = [&](const BoundingSphere& inner) {
    EXPECT_LE(glm::length(inner.center - group.bounds.center) + inner.radius, group.bounds.radius * (1 + 1e-12));
    gain = std::max(gain, inner.gain);
  };
  for (const GroupedOperand& operand : group.operands) {
    holds(operand.bounds);
    cost += operand.cost;
    under.insert(operand.index);
  }
  for (const OperandGroup& half : group.halves) {
    holds(half.bounds);
    cost += half.cost;
    under.merge(check_group(half));
  }
  EXPECT_EQ(group.cost, cost);
  EXPECT_EQ(group.bounds.gain, gain);
  return under;
}

TEST(SubtreeBounds, OperandGroupsSplitAtTheMedianOfTheWidestAxis) {
  for (int axis = 0; axis < 3; ++axis) {
    for (int count : {1, 3, 4, 7, 21}) {
      const OperandGroup root = group_operands(operands_in_a_row(count, axis));
      std::multiset<std::size_t> all;
      for (int i = 0; i < count; ++i) all.insert(static_cast<std::size_t>(i));
      EXPECT_EQ(check_group(root), all) << count << " along axis " << axis;
      if (count <= static_cast<int>(kLeafOperands)) continue;
      // Each half holds the operands on its side of the median along the row.
      ASSERT_EQ(root.halves.size(), 2u);
      double first_high = -1e300, second_low = 1e300;
      for_each_operand(root.halves[0],
                       [&](const GroupedOperand& o) { first_high = std::max(first_high, o.bounds.center[axis]); });
      for_each_operand(root.halves[1],
                       [&](const GroupedOperand& o) { second_low = std::min(second_low, o.bounds.center[axis]); });
      EXPECT_LT(first_high, second_low);
    }
  }
  EXPECT_THROW(group_operands({}), std::logic_error);
}

TEST(SubtreeBounds, GroupedUnionsRenderTheUngatedPicture) {
  // Every buffer, ids and materials included, with soft shadows and a mirror; gates change which
  // operands a step evaluates, never the value, so the pictures are the same bits.
  const std::string scene =
      "camera: {position: [0, 2.5, 4.5], look_at: [0, -0.2, 0]}\n"
      "render: {width: 48, height: 32, subtree_bounds: BOUNDS}\n"
      "sdf:\n  " +
      gallery_union() +
      "lights: [{point: {position: [-2, 4, 3]}}]\n"
      "shading: {shadows: {mode: soft}, reflections: 1}\n";
  const auto with_bounds = [&](const char* bounds) {
    std::string text = scene;
    text.replace(text.find("BOUNDS"), 6, bounds);
    return scene_from_yaml(text);
  };
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.purpose = KernelPurpose::Buffers;
    options.lanes = lanes;
    const RenderResult grouped = render_opencl(with_bounds("sphere"), options);
    const RenderResult plain = render_opencl(with_bounds("none"), options);
    const testing::PlaneComparison planes = testing::compare_planes(grouped.buffers, plain.buffers);
    EXPECT_EQ(planes.differing, "") << "lanes " << lanes;
    EXPECT_GE(planes.compared, 5) << "lanes " << lanes;
  }
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
      // Grouped by place; then with an expensive child gated after the groups, without an
      // unbounded child (the first group ungated), and nested inside a union of its own.
      gallery_union(),
      gallery_union() + "    - menger: {half_size: 0.6, translate: [0, 1.2, 0], color: [1, 0, 1]}",
      gallery_union().substr(gallery_union().find("    - sphere")).insert(0, "union:\n"),
      nested_gallery_union(),
      // A group whose gain (the largest of its children's) overstates the bound inside: a negative
      // least distance compares with 0. At (0.8, -0.1, 0) the plane gives -0.1, the sphere -0.194.
      "union: [{plane: {normal: [0, 1, 0], offset: 0}}, {sphere: {radius: 1}}, {box: {center: [0.5, 0.5, 0], "
      "half_size: [0.1, 0.1, 0.1], step_factor: 0.25}}, {box: {center: [-0.5, 0.5, 0], half_size: [0.1, 0.1, 0.1]}}, "
      "{box: {center: [0, 0.5, 0.5], half_size: [0.1, 0.1, 0.1]}}, {box: {center: [0, 0.5, -0.5], half_size: [0.1, "
      "0.1, 0.1]}}]",
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

// The operand grid of large unions (host/prune/operand_grid.hpp): its pruned evaluation against the
// unpruned one on random trees (every operator kind inside operands, smooth radii from 0 to large,
// transforms, materials) and on every shipped scene, on the kernel at every packet width and
// against the reference; its bound outside the grid; the scale script's scenes through the check;
// and the program's size, which must not grow with the scene.
#include "check/cross_check.hpp"
#include "codegen/kernel_source.hpp"
#include "common/errors.hpp"
#include "prune/operand_grid.hpp"
#include "reference/reference_renderer.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cstdlib>
#include <filesystem>
#include <random>

namespace clmarch {
namespace {

using testing::scene_from_yaml;

std::string vec(const glm::dvec3& v) { return fmt::format("[{:.6g}, {:.6g}, {:.6g}]", v.x, v.y, v.z); }

/// A random operand: a primitive, or a small subtree of every operator kind and of the modifiers
/// that keep a bounding sphere, some transformed or coloured; all bounded, as the grid requires.
std::string random_operand(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), size(0.05, 0.2);
  const auto point = [&] { return glm::dvec3(unit(rng), unit(rng), unit(rng)); };
  const auto primitive = [&](int kind) {
    const glm::dvec3 c = point();
    switch (kind) {
      case 0:
        return fmt::format("sphere: {{center: {}, radius: {:.6g}}}", vec(c), size(rng));
      case 1:
        return fmt::format("box: {{center: {}, half_size: {}}}", vec(c),
                           vec(glm::dvec3(size(rng), size(rng), size(rng))));
      case 2:
        return fmt::format("capsule: {{a: {}, b: {}, radius: {:.6g}}}", vec(c), vec(c + 0.2 * point()),
                           0.5 * size(rng));
      case 3:
        return fmt::format("torus: {{center: {}, major_radius: {:.6g}, minor_radius: {:.6g}}}", vec(c), size(rng),
                           0.3 * size(rng));
      default:
        return fmt::format("round_box: {{center: {}, half_size: [0.1, 0.15, 0.2], radius: 0.03}}", vec(c));
    }
  };
  std::uniform_int_distribution<int> kind(0, 14);
  const int k = kind(rng);
  std::string extra;
  if (k % 3 == 0) extra += fmt::format(", color: {}", vec(0.5 * point() + 0.5));
  if (k % 4 == 1)
    extra += fmt::format(", translate: {}, rotate: {}, scale: 0.8", vec(0.1 * point()), vec(90.0 * point()));
  const std::string a = primitive(k % 5), b = primitive((k + 2) % 5);
  if (k < 5) return fmt::format("{{{}{}}}}}", a.substr(0, a.size() - 1), extra);
  if (k == 5) return fmt::format("{{subtraction: [{{{}}}, {{{}}}]}}", a, b);
  if (k == 6) return fmt::format("{{intersection: [{{{}}}, {{sphere: {{radius: 2}}}}]}}", a);
  if (k == 7) return fmt::format("{{smooth_union: {{k: 0.1, children: [{{{}}}, {{{}}}]{}}}}}", a, b, extra);
  if (k == 8) return fmt::format("{{smooth_subtraction: {{k: 0.05, children: [{{{}}}, {{{}}}]}}}}", a, b);
  if (k == 9)
    return fmt::format("{{smooth_intersection: {{k: 0.05, children: [{{{}}}, {{sphere: {{radius: 2}}}}]}}}}", a);
  // The modifiers of issue 25: 1-Lipschitz maps of one child, and a polar repetition, which is not.
  if (k == 10) return fmt::format("{{elongate: {{h: [0.1, 0, 0.05], children: [{{{}}}]}}}}", a);
  if (k == 11) return fmt::format("{{onion: {{thickness: 0.02, children: [{{{}}}]{}}}}}", a, extra);
  if (k == 12) return fmt::format("{{round: {{radius: 0.03, children: [{{{}}}]}}}}", a);
  if (k == 13) return fmt::format("{{mirror: {{axes: [x, z], children: [{{{}}}]}}}}", a);
  return fmt::format("{{repeat_polar: {{count: 5, children: [{{{}}}]}}}}", a);
}

/// n random operands as the items of a YAML block list, each line starting with indent.
std::string random_operands(unsigned seed, int n, const std::string& indent) {
  std::mt19937 rng(seed);
  std::string lines;
  for (int i = 0; i < n; ++i) lines += indent + "- " + random_operand(rng) + "\n";
  return lines;
}

/// A scene of a union (k = 0) or smooth union of n random operands, with the pruning asked for.
std::string random_union(unsigned seed, int n, double k, const char* pruning) {
  std::string yaml = fmt::format("render: {{pruning: {}}}\nsdf:\n", pruning);
  yaml += k == 0.0 ? "  union:\n    children:\n" : fmt::format("  smooth_union:\n    k: {}\n    children:\n", k);
  return yaml + random_operands(seed, n, "      ");
}

struct UnionCase {
  unsigned seed;
  int operands;
  double k;
};

/// Points inside the grid (equality holds there) and a few outside it (a bound holds there).
std::vector<glm::dvec3> sample_points(unsigned seed, const OperandGrid& grid, int count) {
  std::mt19937 rng(seed * 7 + 1);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < count; ++i) {
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = std::uniform_real_distribution<double>(grid.lower[a] - 0.5, grid.upper[a] + 0.5)(rng);
    points.push_back(p);
  }
  return points;
}

bool inside(const OperandGrid& grid, const glm::dvec3& p) {
  return glm::all(glm::greaterThanEqual(p, grid.lower)) && glm::all(glm::lessThan(p, grid.upper));
}

class OperandGridEquality : public ::testing::TestWithParam<UnionCase> {};

TEST_P(OperandGridEquality, EqualsTheUnprunedUnionInsideAndBoundsItOutside) {
  const UnionCase c = GetParam();
  const Scene pruned = scene_from_yaml(random_union(c.seed, c.operands, c.k, "grid"));
  const Scene full = scene_from_yaml(random_union(c.seed, c.operands, c.k, "none"));
  ASSERT_EQ(grid_union(pruned), &pruned.sdf);
  ASSERT_EQ(grid_union(full), nullptr);
  const OperandGrid grid = build_operand_grid(pruned.sdf, glm::dvec3(0.0));
  const std::vector<glm::dvec3> points = sample_points(c.seed, grid, 4096);
  const double extent = glm::length(grid.upper - grid.lower);
  // Every operand the grid leaves out is a step of the fold that changes nothing but the rounding
  // of b + (a - b) * 1 (the smooth minimum's mix at weight 1): an ulp of the larger value, at most
  // once an operand. A hard union's min rounds nothing.
  const double per_step = 2.0 * FLT_EPSILON * (extent + 1.0);
  const double tolerance = c.k == 0.0 ? 0.0 : per_step * c.operands;
  ASSERT_LT(tolerance, 0.05 * extent) << "a tolerance that large would check nothing";
  OpenClOptions options;
  for (int lanes : {1, 16}) {
    options.lanes = lanes;
    const PointSamples a = eval_points_opencl(pruned, points, options);
    const PointSamples b = eval_points_opencl(full, points, options);
    int compared = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::string where =
          fmt::format("lanes {} point ({}, {}, {})", lanes, points[i].x, points[i].y, points[i].z);
      if (!inside(grid, points[i])) {
        EXPECT_LE(a.distance[i], b.distance[i] + tolerance) << "outside the grid the bound must stay below: " << where;
        EXPECT_GT(a.distance[i], 0.0f) << "no surface lies outside the grid: " << where;
        continue;
      }
      ++compared;
      EXPECT_NEAR(a.distance[i], b.distance[i], tolerance) << where;
      EXPECT_NEAR(a.color_distance[i], b.color_distance[i], tolerance) << where;
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a.albedo[i][ch], b.albedo[i][ch], per_step * c.operands) << where;
    }
    EXPECT_GT(compared, 1000);
  }
}

TEST_P(OperandGridEquality, AgreesWithTheUnprunedReference) {
  const UnionCase c = GetParam();
  const Scene pruned = scene_from_yaml(random_union(c.seed, c.operands, c.k, "grid"));
  const OperandGrid grid = build_operand_grid(pruned.sdf, glm::dvec3(0.0));
  std::vector<glm::dvec3> points = sample_points(c.seed + 100, grid, 2048);
  std::erase_if(points, [&](const glm::dvec3& p) { return !inside(grid, p); });
  OpenClOptions options;
  options.lanes = 16;
  const PointSamples a = eval_points_opencl(pruned, points, options);
  // Float against double over a fold of up to every operand: an ulp of the values met at each step.
  const double tolerance = 4.0 * FLT_EPSILON * (glm::length(grid.upper - grid.lower) + 1.0) * (c.operands + 8);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(a.distance[i], reference_distance(pruned.sdf, points[i]), tolerance)
        << points[i].x << "," << points[i].y;
  }
}

INSTANTIATE_TEST_SUITE_P(RandomTrees, OperandGridEquality,
                         ::testing::Values(UnionCase{1, 64, 0.0}, UnionCase{2, 64, 0.02}, UnionCase{3, 48, 0.3},
                                           UnionCase{4, 40, 2.0}),
                         [](const auto& info) {
                           return fmt::format("seed{}_k{}", info.param.seed, static_cast<int>(info.param.k * 100));
                         });

// Spheres along x, far to near, each within k of the last: every step of the fold blends, so the
// first operand still shapes the value at the near end, although its own distance is far above
// the nearest's (it is left out by the nearest's bound alone). The grid must keep it where it counts.
TEST(OperandGrid, AChainOfBlendsCarriesTheFirstOperandToTheEnd) {
  std::string chain;
  for (int i = 0; i < 12; ++i)
    chain += fmt::format("      - sphere: {{center: [{}, 0, 0], radius: 0.1}}\n", 3.0 - 0.25 * i);
  const std::string body = "  smooth_union:\n    k: 1\n    children:\n" + chain;
  const Scene pruned = scene_from_yaml("render: {pruning: grid}\nsdf:\n" + body);
  const Scene full = scene_from_yaml("render: {pruning: none}\nsdf:\n" + body);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 64; ++i) points.emplace_back(-1.0 + 0.02 * i, 0.05 * (i % 5), 0.0);
  OpenClOptions options;
  options.lanes = 16;
  const PointSamples a = eval_points_opencl(pruned, points, options);
  const PointSamples b = eval_points_opencl(full, points, options);
  // Twelve steps of the fold, each rounding values up to 4 by an ulp or two.
  const double tolerance = 12 * 2 * 4 * FLT_EPSILON;
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(a.distance[i], b.distance[i], tolerance) << points[i].x;
  // Without the first operand the value moves by far more than that (the test can fail).
  Scene without_first = full;
  without_first.sdf.children.erase(without_first.sdf.children.begin());
  const PointSamples c = eval_points_opencl(without_first, points, options);
  double moved = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
    moved = std::max(moved, std::abs(static_cast<double>(c.distance[i]) - b.distance[i]));
  EXPECT_GT(moved, 5 * tolerance);
}

// Blends as operands of a grid: their code in the operand records, and their cells. A chamfered
// pair of concentric spheres falls sqrt 2 times as fast as the point moves (both operands'
// gradients agree), so its value at a cell's centre does not bound it over the cell
// (operator_lipschitz: the grid bounds it by its sphere alone); the pruned union equals the full one.
TEST(OperandGrid, KeepsBlendsSteeperThanOne) {
  std::string body = "  union:\n";
  for (int i = 0; i < 48; ++i) {
    body += fmt::format("    - sphere: {{center: [{}, {}, {}], radius: 0.15}}\n", -3.0 + 0.5 * (i % 12),
                        -0.5 + (i / 12) % 2, (i / 24) * 2.0);
  }
  // Each blob in a ring of small spheres, so that cells between them hold both.
  for (double x : {-2.0, 0.0, 2.0}) {
    body += fmt::format(
        "    - union_chamfer: {{radius: 0.4, translate: [{}, 1.2, 1], children: [{{sphere: {{radius: 0.3}}}}, "
        "{{sphere: {{radius: 0.25}}}}]}}\n",
        x);
    for (int j = 0; j < 8; ++j) {
      const double angle = 0.785398 * j;
      body += fmt::format("    - sphere: {{center: [{}, {}, 1], radius: 0.1}}\n", x + 0.9 * std::cos(angle),
                          1.2 + 0.9 * std::sin(angle));
    }
  }
  const Scene pruned = scene_from_yaml("render: {pruning: grid}\nsdf:\n" + body);
  const Scene full = scene_from_yaml("render: {pruning: none}\nsdf:\n" + body);
  ASSERT_EQ(grid_union(pruned), &pruned.sdf);
  const OperandGrid grid = build_operand_grid(pruned.sdf, glm::dvec3(0.0));
  std::vector<glm::dvec3> points = sample_points(5, grid, 4096);
  std::erase_if(points, [&](const glm::dvec3& p) { return !inside(grid, p); });
  OpenClOptions options;
  options.lanes = 16;
  const PointSamples a = eval_points_opencl(pruned, points, options);
  const PointSamples b = eval_points_opencl(full, points, options);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(a.distance[i], b.distance[i]) << points[i].x << ", " << points[i].y << ", " << points[i].z;
  }
}

TEST(OperandGrid, CellListsAreAscendingNonEmptyAndShort) {
  const int n = 400;
  const Scene scene = scene_from_yaml(random_union(9, n, 0.0, "grid"));
  const OperandGrid grid = build_operand_grid(scene.sdf, glm::dvec3(0.0));
  EXPECT_EQ(grid.cell_start.size(), static_cast<std::size_t>(grid.cell_count()) + 1);
  for (long long c = 0; c < grid.cell_count(); ++c) {
    ASSERT_LT(grid.cell_start[c], grid.cell_start[c + 1]) << "cell " << c << " is empty";
    for (std::uint32_t i = grid.cell_start[c] + 1; i < grid.cell_start[c + 1]; ++i) {
      ASSERT_LT(grid.operands[i - 1], grid.operands[i]) << "cell " << c << " is not in the scene's order";
    }
  }
  // These operands overlap densely (about 30 a unit cube, each up to 0.6 across): a cell keeps
  // those within its nearest's reach plus its own diagonal, far fewer than all.
  const double mean = static_cast<double>(grid.operands.size()) / static_cast<double>(grid.cell_count());
  EXPECT_LT(mean, n / 4.0);
}

// Issue 23: a grid too large for the memory given is refused with both sizes before the cells are
// allocated, or while its lists grow past it; the grid that fits exactly is built.
TEST(OperandGrid, RefusesAGridBeyondTheMemoryGiven) {
  const Scene scene = scene_from_yaml(random_union(9, 400, 0.2, "grid"));
  const OperandGrid grid = build_operand_grid(scene.sdf, glm::dvec3(0.0));
  const std::uint64_t cells = static_cast<std::uint64_t>(grid.cell_count());
  const std::uint64_t first_estimate = grid_host_bytes(grid.cell_count(), cells);
  const std::uint64_t whole = grid_host_bytes(grid.cell_count(), grid.operands.size());
  ASSERT_GT(grid.operands.size(), 2 * cells)
      << "the lists must outgrow the first estimate for the second check to be seen";
  const auto refusal = [&](std::uint64_t bytes) {
    try {
      build_operand_grid(scene.sdf, glm::dvec3(0.0), AvailableMemory{bytes, "a test's budget"});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string early = refusal(first_estimate - 1);
  EXPECT_NE(early.find(fmt::format(
                "the smooth_union of 400 operands needs an operand grid (render.pruning) of {} x {} x {} cells "
                "listing at least {} operands: {} bytes",
                grid.dims.x, grid.dims.y, grid.dims.z, cells, first_estimate)),
            std::string::npos)
      << early;
  EXPECT_NE(early.find(fmt::format("but only {} bytes", first_estimate - 1)), std::string::npos) << early;
  EXPECT_NE(early.find("(a test's budget)"), std::string::npos) << early;
  const std::string growing = refusal((first_estimate + whole) / 2);
  EXPECT_NE(growing.find("listing at least"), std::string::npos) << growing;
  EXPECT_EQ(growing.find(fmt::format("listing at least {} operands", cells)), std::string::npos)
      << "refused only once the lists passed the budget: " << growing;
  EXPECT_EQ(refusal(whole), "");
}

// The largest grid-able union of every shipped scene, taken alone in its own frame, evaluated from
// its grid (render.pruning: grid, whatever its size) equals its unpruned evaluation inside the grid,
// within the same rounding as the random trees above.
TEST(OperandGrid, EqualsTheUnprunedUnionOfEveryShippedScene) {
  int compared_scenes = 0;
  for (const std::string& name : testing::shipped_scene_names()) {
    SCOPED_TRACE(name);
    Scene scene = load_scene_file(testing::source_path("scenes/" + name).string());
    scene.render.pruning = Pruning::Grid;
    const Node* union_node = grid_union(scene);
    if (!union_node) continue;
    Scene pruned;
    pruned.render.pruning = Pruning::Grid;
    pruned.sdf = *union_node;
    pruned.sdf.transform = Transform{};
    Scene full = pruned;
    full.render.pruning = Pruning::None;
    ASSERT_EQ(grid_union(pruned), &pruned.sdf);
    const OperandGrid grid = build_operand_grid(pruned.sdf, glm::dvec3(0.0));
    std::vector<glm::dvec3> points = sample_points(static_cast<unsigned>(compared_scenes) + 5, grid, 2048);
    std::erase_if(points, [&](const glm::dvec3& p) { return !inside(grid, p); });
    const std::size_t operands = pruned.sdf.children.size();
    const double extent = glm::length(grid.upper - grid.lower);
    const double k = is_smooth_operator(pruned.sdf.kind) ? smooth_k(pruned.sdf) : 0.0;
    const double tolerance = k == 0.0 ? 0.0 : 2.0 * FLT_EPSILON * (extent + 1.0) * static_cast<double>(operands);
    const PointSamples a = eval_points_opencl(pruned, points, OpenClOptions{});
    const PointSamples b = eval_points_opencl(full, points, OpenClOptions{});
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_NEAR(a.distance[i], b.distance[i], tolerance) << points[i].x << ", " << points[i].y << ", " << points[i].z;
    }
    EXPECT_GT(points.size(), 500u);
    ++compared_scenes;
  }
  EXPECT_GE(compared_scenes, 3) << "most shipped scenes have a union of bounded operands";
}

// The scenes scripts/large-scene.py writes (issue 23: random spheres in a union, a smooth-unioned
// molecule, boxes less capsules), at two sizes each, pass the cross-check that clmarch check runs,
// against the unpruned double reference.
TEST(OperandGrid, ScriptScenesPassTheCheck) {
  const testing::TempDir folder;
  for (const char* kind : {"spheres", "molecule", "parts"}) {
    for (int n : {60, 300}) {
      SCOPED_TRACE(fmt::format("{} {}", kind, n));
      const std::filesystem::path file = folder / fmt::format("{}-{}.yaml", kind, n);
      const std::string command = fmt::format(
          "python3 {} {} {} > {}", testing::shell_quote(testing::source_path("scripts/large-scene.py").string()), kind,
          n, testing::shell_quote(file.string()));
      ASSERT_EQ(std::system(command.c_str()), 0) << command;
      Scene scene = load_scene_file(file.string());
      scene.render.width = 64;
      scene.render.height = 36;
      ASSERT_NE(grid_union(scene), nullptr) << "render.pruning: auto takes the grid from 48 operands";
      OpenClOptions options;
      options.lanes = 16;
      const FrameBuffers opencl = render_opencl(scene, options).buffers;
      const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
      EXPECT_TRUE(report.passed()) << report.to_text();
      EXPECT_GT(report.both_hit, 64 * 36 / 10);
    }
  }
}

TEST(OperandGrid, AutoPrunesOnlyLargeUnionsAndNoneNever) {
  std::string small = random_union(3, static_cast<int>(kAutoGridOperands) - 1, 0.0, "auto");
  std::string large = random_union(3, static_cast<int>(kAutoGridOperands), 0.0, "auto");
  EXPECT_EQ(grid_union(scene_from_yaml(small)), nullptr);
  const Scene scene = scene_from_yaml(large);
  EXPECT_EQ(grid_union(scene), &scene.sdf);
  // The largest union is chosen, wherever it is in the tree.
  const Scene nested = scene_from_yaml(
      "sdf:\n  union:\n    - plane: {normal: [0, 1, 0], offset: 1}\n"
      "    - smooth_union:\n        k: 0.1\n        children:\n" +
      random_operands(3, 60, "          "));
  ASSERT_EQ(nested.sdf.children.size(), 2u);
  EXPECT_EQ(grid_union(nested), &nested.sdf.children[1]);
}

TEST(OperandGrid, TheProgramDoesNotGrowWithTheScene) {
  const KernelOptions options(KernelPurpose::Shaded, 16);
  const std::string hundred = generate_kernel_source(scene_from_yaml(random_union(4, 100, 0.0, "grid")), options);
  const std::string thousand = generate_kernel_source(scene_from_yaml(random_union(4, 1000, 0.0, "grid")), options);
  // The same shapes of operands give the same code; only the comments' figures differ.
  EXPECT_LT(std::abs(static_cast<long long>(thousand.size()) - static_cast<long long>(hundred.size())), 64);
}

TEST(OperandGrid, RenderPruningIsASettingWithNamedValues) {
  EXPECT_NE(testing::error_of("render: {pruning: octree}\nsdf: {sphere: {}}\n").find("render.pruning"),
            std::string::npos);
}

}  // namespace
}  // namespace clmarch

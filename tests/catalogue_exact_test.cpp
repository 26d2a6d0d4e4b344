// The later catalogue primitives' reference distances checked against geometry itself, not
// against a formula: the distance to the field's own zero set, found by brute force on a grid, and
// a gradient of length 1 outside. An exact kind must meet both; a bound kind must stay at or
// below the brute-force distance.
#include "reference/reference_sdf.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace clmarch {
namespace {

struct ShapeCase {
  const char* name;
  const char* sdf_yaml;
  /// The shape lies well inside the cube [-extent, extent]^3.
  double extent;
  bool exact;
};

const ShapeCase kShapes[] = {
    {"cone", "cone: {center: [0, 0.5, 0], angle: 35, height: 1}", 1.2, true},
    {"rounded_cylinder", "rounded_cylinder: {radius: 0.7, half_height: 0.5, edge_radius: 0.2}", 1.0, true},
    {"round_cone", "round_cone: {a: [-0.3, -0.4, 0.1], b: [0.4, 0.5, -0.2], radius_a: 0.45, radius_b: 0.2}", 1.2, true},
    {"capped_cylinder", "capped_cylinder: {a: [-0.4, -0.5, 0.2], b: [0.3, 0.4, -0.3], radius: 0.35}", 1.0, true},
    {"frustum", "frustum: {a: [-0.3, -0.5, 0.2], b: [0.3, 0.5, -0.2], radius_a: 0.55, radius_b: 0.2}", 1.0, true},
    {"capped_torus", "capped_torus: {angle: 110, major_radius: 0.7, minor_radius: 0.2}", 1.2, true},
    {"link", "link: {half_length: 0.3, major_radius: 0.4, minor_radius: 0.15}", 1.2, true},
    {"cut_sphere", "cut_sphere: {radius: 0.9, cut_height: -0.3}", 1.0, true},
    {"pyramid", "pyramid: {center: [0, -0.5, 0], half_width: 0.6, height: 1.2}", 1.0, true},
    {"triangle", "triangle: {a: [-0.7, -0.5, 0.1], b: [0.6, -0.3, -0.4], c: [0.1, 0.7, 0.3], thickness: 0.15}", 1.0,
     true},
    {"quad",
     "quad: {a: [-0.6, -0.6, -0.3], b: [0.6, -0.6, 0.3], c: [0.6, 0.6, 0.3], d: [-0.6, 0.6, -0.3], thickness: 0.15}",
     1.0, true},
    {"triangular_prism", "triangular_prism: {radius: 0.8, half_length: 0.6}", 1.0, false},
    {"solid_angle", "solid_angle: {center: [0, -0.2, 0], angle: 55, radius: 0.9}", 1.0, true},
    {"solid_angle_wide", "solid_angle: {angle: 130, radius: 0.9}", 1.0, true},
    {"cut_hollow_sphere", "cut_hollow_sphere: {radius: 0.8, cut_height: 0.3, thickness: 0.12}", 1.0, true},
    {"death_star", "death_star: {radius: 0.9, carve_radius: 0.6, carve_distance: 0.8}", 1.0, true},
    {"rhombus", "rhombus: {half_width: 0.8, half_depth: 0.4, half_height: 0.2, corner_radius: 0.1}", 1.0, true},
};

// The grid's cells: the zero set is found on their edges, so a surface point is within a cell's
// diagonal of a found one.
constexpr int kCells = 48;

/// Points of the field's zero set: where it changes sign along a grid edge, refined by bisection.
std::vector<glm::dvec3> zero_set(const Node& node, double extent) {
  const double step = 2.0 * extent / kCells;
  const auto at = [&](int i, int j, int k) {
    return glm::dvec3(-extent + i * step, -extent + j * step, -extent + k * step);
  };
  std::vector<double> field;
  field.reserve((kCells + 1) * (kCells + 1) * (kCells + 1));
  for (int i = 0; i <= kCells; ++i) {
    for (int j = 0; j <= kCells; ++j) {
      for (int k = 0; k <= kCells; ++k) field.push_back(reference_distance(node, at(i, j, k)));
    }
  }
  const auto value = [&](int i, int j, int k) {
    return field[(static_cast<std::size_t>(i) * (kCells + 1) + j) * (kCells + 1) + k];
  };
  std::vector<glm::dvec3> surface;
  for (int i = 0; i <= kCells; ++i) {
    for (int j = 0; j <= kCells; ++j) {
      for (int k = 0; k <= kCells; ++k) {
        const int next[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& n : next) {
          if (n[0] > kCells || n[1] > kCells || n[2] > kCells) continue;
          if ((value(i, j, k) < 0.0) == (value(n[0], n[1], n[2]) < 0.0)) continue;
          glm::dvec3 inside = at(i, j, k), outside = at(n[0], n[1], n[2]);
          if (value(i, j, k) >= 0.0) std::swap(inside, outside);
          for (int b = 0; b < 40; ++b) {
            const glm::dvec3 middle = 0.5 * (inside + outside);
            (reference_distance(node, middle) < 0.0 ? inside : outside) = middle;
          }
          surface.push_back(0.5 * (inside + outside));
        }
      }
    }
  }
  return surface;
}

class CatalogueShape : public ::testing::TestWithParam<ShapeCase> {};

TEST_P(CatalogueShape, DistanceIsTheBruteForceDistanceToItsSurface) {
  const ShapeCase& shape = GetParam();
  const Node node = testing::scene_from_yaml(std::string("sdf:\n  ") + shape.sdf_yaml + "\n").sdf;
  const std::vector<glm::dvec3> surface = zero_set(node, shape.extent);
  ASSERT_GT(surface.size(), 500u);
  const double diagonal = std::sqrt(3.0) * 2.0 * shape.extent / kCells;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-shape.extent, shape.extent);
  for (int n = 0; n < 40; ++n) {
    const glm::dvec3 p(coord(rng), coord(rng), coord(rng));
    double brute = INFINITY;
    for (const glm::dvec3& s : surface) brute = std::min(brute, glm::length(p - s));
    const double d = std::abs(reference_distance(node, p));
    SCOPED_TRACE(::testing::Message() << shape.name << " at (" << p.x << ", " << p.y << ", " << p.z << ")");
    // Never past the surface; the found points are on it (to bisection's 1e-12).
    EXPECT_LE(d, brute + 1e-9);
    // Exact: the surface is no farther than the field says, up to the gaps between found points.
    if (shape.exact) {
      EXPECT_GE(d, brute - diagonal);
    }
  }
}

TEST_P(CatalogueShape, GradientHasUnitLengthOutside) {
  const ShapeCase& shape = GetParam();
  const Node node = testing::scene_from_yaml(std::string("sdf:\n  ") + shape.sdf_yaml + "\n").sdf;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> coord(-2.0 * shape.extent, 2.0 * shape.extent);
  constexpr double kStep = 1e-6;
  // Central differences of double distances of order 1: about 1e-10 / kStep of rounding.
  constexpr double kSlack = 1e-4;
  int outside = 0, unit = 0;
  while (outside < 2000) {
    const glm::dvec3 p(coord(rng), coord(rng), coord(rng));
    if (reference_distance(node, p) < 0.01) continue;
    ++outside;
    glm::dvec3 g;
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 e(0.0);
      e[a] = kStep;
      g[a] = (reference_distance(node, p + e) - reference_distance(node, p - e)) / (2.0 * kStep);
    }
    const double slope = glm::length(g);
    EXPECT_LE(slope, 1.0 + kSlack) << shape.name << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
    if (slope >= 1.0 - kSlack) ++unit;
  }
  // Only points within kStep of the medial axis (a kink of the field) may have a shorter gradient.
  if (shape.exact) {
    EXPECT_GE(unit, outside - 2) << shape.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, CatalogueShape, ::testing::ValuesIn(kShapes),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace clmarch

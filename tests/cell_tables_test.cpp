// The cell tables of marching cubes and tetrahedra: each case's triangles join the edges the level
// crosses, and grids of random corner signs marched with them (a marcher written here, keyed by
// grid edge in a map) give closed, consistently oriented surfaces, also where faces are ambiguous.
#include "mesh/cell_tables.hpp"
#include "support/mesh_topology.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <tuple>

namespace clmarch {
namespace {

class CellTables : public ::testing::TestWithParam<CellMethod> {};

std::string cell_method_name(const ::testing::TestParamInfo<CellMethod>& info) {
  return std::string(kCellMethodNames[static_cast<int>(info.param)]);
}

bool corner_below(int below, int corner) { return ((below >> corner) & 1) != 0; }

TEST_P(CellTables, TrianglesJoinTheCrossedEdgesAndCubesUseEveryOne) {
  const CellTable& table = cell_table(GetParam());
  const EdgeSteps& steps = edge_steps(GetParam());
  for (int below = 0; below < 256; ++below) {
    const CellCase& cell = table[static_cast<std::size_t>(below)];
    std::set<std::pair<int, int>> used;
    for (int t = 0; t < cell.count; ++t) {
      std::set<std::pair<int, int>> corners;
      for (const CellEdge& e : cell.triangles[static_cast<std::size_t>(t)]) {
        ASSERT_EQ(e.from & e.step, 0) << below;
        ASSERT_GE(steps.slot[e.step], 0) << "an edge of a step the method does not use, case " << below;
        ASSERT_NE(corner_below(below, e.from), corner_below(below, e.from | e.step)) << "case " << below;
        corners.insert({e.from, e.step});
        used.insert({e.from, e.step});
      }
      ASSERT_EQ(corners.size(), 3u) << "a triangle with two corners on one edge, case " << below;
    }
    if (GetParam() != CellMethod::Cubes) continue;
    // Marching cubes puts a vertex on every crossed edge of the cell, and at most 5 triangles.
    std::set<std::pair<int, int>> crossed;
    for (int from = 0; from < 8; ++from) {
      for (int step : {1, 2, 4}) {
        if ((from & step) == 0 && corner_below(below, from) != corner_below(below, from | step))
          crossed.insert({from, step});
      }
    }
    EXPECT_EQ(used, crossed) << "case " << below;
    EXPECT_LE(cell.count, 5) << "case " << below;
  }
  EXPECT_EQ(table[0].count, 0);
  EXPECT_EQ(table[255].count, 0);
}

TEST_P(CellTables, RandomSignsGiveClosedSurfaces) {
  // n^3 grid points with random sides, the outer layer above the level so that every surface
  // closes inside; vertices keyed by (grid point, step).
  constexpr int n = 8;
  const CellTable& table = cell_table(GetParam());
  std::mt19937 rng(7);
  for (int round = 0; round < 40; ++round) {
    std::bernoulli_distribution below_level(round % 2 == 0 ? 0.5 : 0.3);
    std::vector<int> below(n * n * n, 0);
    const auto at = [&](int x, int y, int z) { return (z * n + y) * n + x; };
    for (int z = 1; z < n - 1; ++z)
      for (int y = 1; y < n - 1; ++y)
        for (int x = 1; x < n - 1; ++x) below[at(x, y, z)] = below_level(rng);
    std::map<std::tuple<int, int, int, int>, std::uint32_t> vertex_of;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (int z = 0; z + 1 < n; ++z)
      for (int y = 0; y + 1 < n; ++y)
        for (int x = 0; x + 1 < n; ++x) {
          int cell_case = 0;
          for (int c = 0; c < 8; ++c) cell_case |= below[at(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1))] << c;
          const CellCase& cell = table[static_cast<std::size_t>(cell_case)];
          for (int t = 0; t < cell.count; ++t) {
            std::array<std::uint32_t, 3> triangle{};
            for (int k = 0; k < 3; ++k) {
              const CellEdge& e = cell.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
              const auto key = std::tuple(x + (e.from & 1), y + (e.from >> 1 & 1), z + (e.from >> 2 & 1), int{e.step});
              triangle[static_cast<std::size_t>(k)] =
                  vertex_of.try_emplace(key, static_cast<std::uint32_t>(vertex_of.size())).first->second;
            }
            triangles.push_back(triangle);
          }
        }
    ASSERT_FALSE(triangles.empty());
    SCOPED_TRACE(round);
    testing::expect_watertight(triangles);
    if (HasFailure()) return;
  }
}

TEST_P(CellTables, ACornerBelowIsCutOffFacingAway) {
  // Counter-clockwise seen from above the level: the normal of corner 0's triangle (on the edges'
  // midpoints) points away from the corner, towards the cell's inside.
  const CellCase& cell = cell_table(GetParam())[1];
  ASSERT_GE(cell.count, 1);
  const auto mid = [](const CellEdge& e) {
    const int to = e.from | e.step;
    return 0.5 *
           glm::dvec3((e.from & 1) + (to & 1), (e.from >> 1 & 1) + (to >> 1 & 1), (e.from >> 2 & 1) + (to >> 2 & 1));
  };
  for (int t = 0; t < cell.count; ++t) {
    const auto& tri = cell.triangles[static_cast<std::size_t>(t)];
    const glm::dvec3 normal = glm::cross(mid(tri[1]) - mid(tri[0]), mid(tri[2]) - mid(tri[0]));
    EXPECT_GT(glm::dot(normal, glm::dvec3(1.0)), 0.0) << t;
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, CellTables, ::testing::Values(CellMethod::Cubes, CellMethod::Tetrahedra),
                         cell_method_name);

}  // namespace
}  // namespace clmarch

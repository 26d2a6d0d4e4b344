// BrickSurface on a field of random signs: the vertices numbered brick by brick and found in their
// owners' edge sets give the triangles a plain marcher over the whole grid gives (keyed by grid edge
// in a map); bricks left out next to crossed faces are sampled anyway, so that a mesh started from
// one brick is the whole grid's.
#include "mesh/brick_surface.hpp"
#include "support/mesh_topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace clmarch {
namespace {

using EdgeKey = std::tuple<int, int, int, int>;
using KeyTriangle = std::array<EdgeKey, 3>;

/// The highest grid coordinate of the noise: the grid's points run up to 24, so the surface stays a
/// cell inside it, as a scene's does.
constexpr int kNoiseInside = 21;

/// Values of a hash of the grid point: below 0 on about half the points of [2, high]^3, 1 elsewhere.
float noise_value(const glm::ivec3& p, int high = kNoiseInside) {
  if (glm::any(glm::lessThan(p, glm::ivec3(2))) || glm::any(glm::greaterThan(p, glm::ivec3(high)))) return 1.0f;
  std::uint32_t h = static_cast<std::uint32_t>(p.x) * 73856093u ^ static_cast<std::uint32_t>(p.y) * 19349663u ^
                    static_cast<std::uint32_t>(p.z) * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return static_cast<float>(h % 1000) / 500.0f - 1.0f;
}

/// A field known at grid points only: vertices stay halfway along their edges.
class GridNoiseField final : public MeshField {
 public:
  int bricks_sampled = 0;
  int high = kNoiseInside;

  std::vector<float> distances(const std::vector<glm::dvec3>& offsets) override {
    std::vector<float> out;
    for (const glm::dvec3& p : offsets) out.push_back(noise_value(glm::ivec3(glm::round(p)), high));
    return out;
  }
  void sample_bricks(std::span<const glm::ivec3> corners, int side, double, std::span<float> out) override {
    std::size_t i = 0;
    for (const glm::ivec3& corner : corners) {
      ++bricks_sampled;
      for (int z = 0; z < side; ++z)
        for (int y = 0; y < side; ++y)
          for (int x = 0; x < side; ++x) out[i++] = noise_value(corner + glm::ivec3(x, y, z), high);
    }
  }
  void place_vertices(std::span<const EdgeSeed>, double, const PlacementSettings&,
                      std::span<PlacedVertex> out) override {
    for (PlacedVertex& v : out) v = {0.5f, glm::vec3(0.0f), glm::vec3(0.0f), 0};
  }
};

MeshGrid noise_grid() {
  MeshGrid grid;
  grid.cell = 1.0;
  grid.cells = glm::ivec3(24);
  grid.bricks = glm::ivec3(3);
  return grid;
}

/// Rotated so that the smallest key comes first (the winding kept).
KeyTriangle canonical(KeyTriangle t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

std::set<KeyTriangle> marched_by_brick_surface(CellMethod method, const std::vector<glm::ivec3>& start,
                                               int& bricks_sampled) {
  GridNoiseField field;
  BrickSurface surface(noise_grid(), 0.0, method);
  surface.sample(field, start, std::size_t{1} << 12, nullptr);
  surface.march();
  bricks_sampled = field.bricks_sampled;
  std::vector<EdgeSeed> seeds;
  for (std::size_t b = 0; b < surface.bricks(); ++b) {
    EXPECT_EQ(surface.first_vertex(b), seeds.size());
    surface.append_seeds(b, seeds);
  }
  EXPECT_EQ(surface.vertices(), seeds.size());
  EXPECT_EQ(surface.dropped_triangles(), 0u);
  std::vector<MeshTriangle> triangles;
  surface.append_triangles(0, surface.bricks(), triangles);
  EXPECT_EQ(triangles.size(), surface.triangles());
  testing::expect_watertight(triangles);
  std::set<KeyTriangle> out;
  for (const auto& t : triangles) {
    KeyTriangle keys;
    for (int k = 0; k < 3; ++k) {
      const EdgeSeed& s = seeds.at(t[static_cast<std::size_t>(k)]);
      keys[static_cast<std::size_t>(k)] = {s.point.x, s.point.y, s.point.z, s.step};
    }
    EXPECT_TRUE(out.insert(canonical(keys)).second);
  }
  return out;
}

std::set<KeyTriangle> marched_whole(CellMethod method, int high = kNoiseInside) {
  const CellTable& table = cell_table(method);
  std::set<KeyTriangle> out;
  for (int z = 0; z < 24; ++z)
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x) {
        int cell_case = 0;
        for (int c = 0; c < 8; ++c)
          cell_case |= (noise_value({x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)}, high) < 0) << c;
        const CellCase& cell = table[static_cast<std::size_t>(cell_case)];
        for (int t = 0; t < cell.count; ++t) {
          KeyTriangle keys;
          for (int k = 0; k < 3; ++k) {
            const CellEdge& e = cell.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
            keys[static_cast<std::size_t>(k)] = {x + (e.from & 1), y + (e.from >> 1 & 1), z + (e.from >> 2 & 1),
                                                 e.step};
          }
          out.insert(canonical(keys));
        }
      }
  return out;
}

class BrickSurfaceNoise : public ::testing::TestWithParam<CellMethod> {};

TEST_P(BrickSurfaceNoise, EveryBrickGivesTheWholeGridsTriangles) {
  std::vector<glm::ivec3> all;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) all.emplace_back(x, y, z);
  int sampled = 0;
  const std::set<KeyTriangle> bricks = marched_by_brick_surface(GetParam(), all, sampled);
  EXPECT_EQ(sampled, 27);
  const std::set<KeyTriangle> whole = marched_whole(GetParam());
  EXPECT_GT(whole.size(), 1000u);
  EXPECT_TRUE(bricks == whole) << bricks.size() << " triangles by bricks, " << whole.size() << " by the whole grid";
}

TEST_P(BrickSurfaceNoise, BricksBesideCrossedFacesAreSampledToo) {
  // Started from the middle brick alone, as if pruning had dropped the others: the surface crosses
  // its faces, so its neighbours are sampled, and theirs, until the mesh is the whole grid's.
  int sampled = 0;
  const std::set<KeyTriangle> bricks = marched_by_brick_surface(GetParam(), {glm::ivec3(1)}, sampled);
  EXPECT_EQ(sampled, 27);
  EXPECT_TRUE(bricks == marched_whole(GetParam()));
}

TEST_P(BrickSurfaceNoise, TrianglesPastTheGridAreLeftOutAndTheCountIsExact) {
  // The noise up to the grid's last points: cells of the last bricks use edges whose lower ends lie
  // on the grid's upper faces, owned by bricks past the grid. Their triangles are left out, and
  // the count announced before any triangle is made is the number made.
  GridNoiseField field;
  field.high = 24;
  BrickSurface surface(noise_grid(), 0.0, GetParam());
  std::vector<glm::ivec3> all;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) all.emplace_back(x, y, z);
  surface.sample(field, all, std::size_t{1} << 12, nullptr);
  surface.march();
  std::vector<MeshTriangle> triangles;
  surface.append_triangles(0, surface.bricks(), triangles);
  ASSERT_EQ(triangles.size(), surface.triangles());
  std::size_t past_the_grid = 0;
  for (const KeyTriangle& t : marched_whole(GetParam(), 24)) {
    past_the_grid += std::any_of(t.begin(), t.end(), [](const EdgeKey& e) {
      return std::get<0>(e) == 24 || std::get<1>(e) == 24 || std::get<2>(e) == 24;
    });
  }
  EXPECT_GT(past_the_grid, 100u);
  EXPECT_EQ(surface.dropped_triangles(), past_the_grid);
  EXPECT_EQ(triangles.size() + past_the_grid, marched_whole(GetParam(), 24).size());
  for (const MeshTriangle& t : triangles) {
    for (const std::uint32_t v : t) ASSERT_LT(v, surface.vertices());
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, BrickSurfaceNoise, ::testing::Values(CellMethod::Cubes, CellMethod::Tetrahedra),
                         [](const ::testing::TestParamInfo<CellMethod>& info) {
                           return std::string(kCellMethodNames[static_cast<int>(info.param)]);
                         });

}  // namespace
}  // namespace clmarch

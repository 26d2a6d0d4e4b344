// Triangles of the tetrahedra of each cell.
#include "mesh/tetra_surface.hpp"

#include <algorithm>

namespace clmarch {
namespace {

/// The corner of a cell with bits (x 1, y 2, z 4), as an offset in cells.
glm::ivec3 corner_offset(int bits) { return {bits & 1, (bits >> 1) & 1, (bits >> 2) & 1}; }

/// Kuhn's six tetrahedra of the unit cube: each walks from corner 0 to corner 7 along the axes in
/// one of their six orders, so its corners' bit sets nest (every edge goes from a subset to a
/// superset: the edge's lower end and step are well defined).
constexpr std::array<std::array<int, 4>, 6> kTetrahedra = {{
    {0, 1, 3, 7},
    {0, 1, 5, 7},
    {0, 2, 3, 7},
    {0, 2, 6, 7},
    {0, 4, 5, 7},
    {0, 4, 6, 7},
}};

}  // namespace

TetraSurface::TetraSurface(const MeshGrid& grid, double level) : grid_(grid), level_(level) {}

std::uint32_t TetraSurface::vertex(const glm::ivec3& low, int step, const glm::dvec3& below, const glm::dvec3& above,
                                   float below_value, float above_value) {
  const auto points = glm::u64vec3(grid_.cells + 1);
  const std::uint64_t key =
      ((static_cast<std::uint64_t>(low.z) * points.y + static_cast<std::uint64_t>(low.y)) * points.x +
       static_cast<std::uint64_t>(low.x)) *
          8 +
      static_cast<std::uint64_t>(step);
  const auto [it, is_new] = by_edge_.try_emplace(key, static_cast<std::uint32_t>(vertices_.size()));
  if (is_new) {
    const double span = static_cast<double>(above_value) - below_value;
    const double t = span > 0.0 ? std::clamp((level_ - below_value) / span, 0.0, 1.0) : 0.5;
    vertices_.push_back({below, above, below_value, above_value, below + t * (above - below), 0});
  }
  return it->second;
}

void TetraSurface::add_brick(const glm::ivec3& brick, std::span<const float> samples) {
  const glm::ivec3 first = brick * kBrickCells;
  const auto sample = [&](const glm::ivec3& local) {
    return samples[static_cast<std::size_t>((local.z * kBrickSamples + local.y) * kBrickSamples + local.x)];
  };
  for (int z = 0; z < kBrickCells; ++z) {
    for (int y = 0; y < kBrickCells; ++y) {
      for (int x = 0; x < kBrickCells; ++x) {
        const glm::ivec3 cell(x, y, z);
        std::array<float, 8> value{};
        int below = 0;
        for (int c = 0; c < 8; ++c) {
          value[c] = sample(cell + corner_offset(c));
          below += value[c] < level_;
        }
        if (below == 0 || below == 8) continue;
        ++surface_cells_;
        const glm::ivec3 global = first + cell;
        const auto point = [&](int c) { return glm::dvec3(global + corner_offset(c)) * grid_.cell; };
        for (const auto& tet : kTetrahedra) {
          std::array<int, 4> low_side{}, high_side{};
          int lows = 0, highs = 0;
          for (int c : tet) (value[c] < level_ ? low_side[lows++] : high_side[highs++]) = c;
          if (lows == 0 || highs == 0) continue;
          const auto edge = [&](int a, int b) {
            // a below, b above; the edge runs from the corner with fewer bits to the other.
            const int from = std::min(a, b), to = std::max(a, b);
            return vertex(global + corner_offset(from), to ^ from, point(a), point(b), value[a], value[b]);
          };
          // Orientation: counter-clockwise seen from above the level. Judged on the edges'
          // midpoints, whose triangles are never degenerate (interpolated vertices can coincide),
          // so that neighbouring triangles always agree.
          glm::dvec3 up(0.0);
          for (int k = 0; k < highs; ++k) up += point(high_side[k]) / static_cast<double>(highs);
          for (int k = 0; k < lows; ++k) up -= point(low_side[k]) / static_cast<double>(lows);
          const auto mid = [&](std::uint32_t v) { return 0.5 * (vertices_[v].below + vertices_[v].above); };
          const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
            const glm::dvec3 n = glm::cross(mid(b) - mid(a), mid(c) - mid(a));
            triangles_.push_back(glm::dot(n, up) > 0.0 ? std::array{a, b, c} : std::array{a, c, b});
          };
          if (lows == 1 || highs == 1) {
            const bool one_low = lows == 1;
            const int apex = one_low ? low_side[0] : high_side[0];
            const std::array<int, 4>& others = one_low ? high_side : low_side;
            std::array<std::uint32_t, 3> v{};
            for (int k = 0; k < 3; ++k) v[k] = one_low ? edge(apex, others[k]) : edge(others[k], apex);
            add(v[0], v[1], v[2]);
          } else {
            // A quad around the tetrahedron: low0-high0, low0-high1, low1-high1, low1-high0.
            const std::uint32_t a = edge(low_side[0], high_side[0]), b = edge(low_side[0], high_side[1]);
            const std::uint32_t c = edge(low_side[1], high_side[1]), d = edge(low_side[1], high_side[0]);
            add(a, b, c);
            add(a, c, d);
          }
        }
      }
    }
  }
}

}  // namespace clmarch

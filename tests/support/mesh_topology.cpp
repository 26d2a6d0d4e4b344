// Edge pairing by sorting, so that meshes of millions of triangles are checked in a second.
#include "support/mesh_topology.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

namespace clmarch::testing {

EdgeCounts edge_counts(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> directed;
  directed.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) directed.emplace_back(t[k], t[(k + 1) % 3]);
  }
  std::sort(directed.begin(), directed.end());
  EdgeCounts counts;
  for (std::size_t i = 0; i < directed.size();) {
    std::size_t j = i;
    while (j < directed.size() && directed[j] == directed[i]) ++j;
    if (j - i > 1) ++counts.repeated;
    const std::pair reverse{directed[i].second, directed[i].first};
    if (!std::binary_search(directed.begin(), directed.end(), reverse)) ++counts.open;
    if (directed[i].first < directed[i].second) ++counts.edges;
    i = j;
  }
  return counts;
}

void expect_watertight(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  const EdgeCounts counts = edge_counts(triangles);
  EXPECT_EQ(counts.open, 0u) << "directed edges without their reverse";
  EXPECT_EQ(counts.repeated, 0u) << "directed edges in two triangles";
}

long long euler_characteristic(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::vector<std::uint32_t> used;
  for (const auto& t : triangles) used.insert(used.end(), t.begin(), t.end());
  std::sort(used.begin(), used.end());
  const auto vertices = static_cast<long long>(std::unique(used.begin(), used.end()) - used.begin());
  return vertices - static_cast<long long>(edge_counts(triangles).edges) + static_cast<long long>(triangles.size());
}

double enclosed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

}  // namespace clmarch::testing

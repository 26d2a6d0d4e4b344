// The watertightness oracle of the mesher's tests (every edge once in each direction, as libfive's
// mesh checks have it) and the figures of a closed mesh: Euler characteristic and enclosed volume.
#pragma once

#include "mesh/triangle_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace clmarch::testing {

/// How the triangles' edges pair up.
struct EdgeCounts {
  std::uint64_t edges = 0;
  /// Directed edges without their reverse (a hole, or a neighbour turned the other way).
  std::uint64_t open = 0;
  /// Directed edges in more than one triangle (a fold, or more than two triangles on an edge).
  std::uint64_t repeated = 0;
};
EdgeCounts edge_counts(const std::vector<std::array<std::uint32_t, 3>>& triangles);

/// Every directed edge in exactly one triangle and its reverse in exactly one: a closed,
/// consistently oriented, edge-manifold surface.
void expect_watertight(const std::vector<std::array<std::uint32_t, 3>>& triangles);

/// V - E + F, V counting the vertices the triangles use: 2 per sphere, 0 per torus.
long long euler_characteristic(const std::vector<std::array<std::uint32_t, 3>>& triangles);

/// The volume a closed mesh encloses (positive when its triangles are counter-clockwise seen from
/// outside), by the divergence theorem.
double enclosed_volume(const TriangleMesh& mesh);

}  // namespace clmarch::testing

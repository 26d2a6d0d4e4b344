// Comparisons of a mesh with what a reader gave back, shared by the mesh writers' tests.
#pragma once

#include "mesh/mesh_writers.hpp"
#include "support/mesh_readers.hpp"

#include <filesystem>
#include <vector>

namespace clmarch::testing {

/// What a file should give back for each vertex of a mesh, and how closely.
struct Expected {
  /// Largest difference of a coordinate; each test names its reason.
  double position_tolerance = 0.0;
  /// The normal each vertex should come back with; empty: not checked.
  std::vector<glm::dvec3> normals{};
  double normal_tolerance = 0.0;
  /// The colour each vertex should come back with; empty: not checked.
  std::vector<glm::dvec3> colors{};
  double color_tolerance = 0.0;
};

/// Checks that read has mesh's triangles in order, each with its corners in the same cyclic order
/// (the winding kept), at positions within tolerance, and the normals and colours expected.
void expect_same_triangles(const TriangleMesh& mesh, const ReadTriangles& read, const Expected& expected);

/// Writes mesh to path and commits it.
void write_committed(const std::filesystem::path& path, const TriangleMesh& mesh, MeshFormat format,
                     MeshPrecision precision = MeshPrecision::Float);

}  // namespace clmarch::testing

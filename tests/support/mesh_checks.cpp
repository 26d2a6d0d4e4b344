// Triangle-by-triangle comparison of a mesh with a reader's triangles.
#include "support/mesh_checks.hpp"

#include "common/atomic_file.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace clmarch::testing {
namespace {

/// Largest coordinate difference of a and b.
double distance(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

/// The rotation r for which corner c of read is vertex triangle[(c + r) % 3] within tolerance, or -1.
int matching_rotation(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& triangle,
                      const std::array<ReadCorner, 3>& read, double tolerance) {
  for (int r = 0; r < 3; ++r) {
    bool all = true;
    for (int c = 0; c < 3; ++c)
      all = all && distance(read[c].position, mesh.positions[triangle[(c + r) % 3]]) <= tolerance;
    if (all) return r;
  }
  return -1;
}

}  // namespace

void expect_same_triangles(const TriangleMesh& mesh, const ReadTriangles& read, const Expected& expected) {
  ASSERT_EQ(read.triangles.size(), mesh.triangles.size());
  EXPECT_EQ(read.distinct_positions(), mesh.positions.size()) << "every vertex, none merged or split";
  int failures = 0;
  for (std::size_t t = 0; t < mesh.triangles.size() && failures < 5; ++t) {
    const std::array<std::uint32_t, 3>& triangle = mesh.triangles[t];
    const int r = matching_rotation(mesh, triangle, read.triangles[t], expected.position_tolerance);
    if (r < 0) {
      ADD_FAILURE() << "triangle " << t << " has other corners or the other winding; first corner read at ("
                    << read.triangles[t][0].position.x << ", " << read.triangles[t][0].position.y << ", "
                    << read.triangles[t][0].position.z << ")";
      ++failures;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const ReadCorner& corner = read.triangles[t][c];
      const std::uint32_t vertex = triangle[(c + r) % 3];
      const auto check = [&](const char* what, const std::optional<glm::dvec3>& value,
                             const std::vector<glm::dvec3>& wanted, double tolerance) {
        if (wanted.empty()) return;
        const double error = value ? distance(*value, wanted[vertex]) : std::numeric_limits<double>::infinity();
        if (error <= tolerance) return;
        ADD_FAILURE() << what << " of vertex " << vertex << (value ? " off by " + std::to_string(error) : " missing");
        ++failures;
      };
      check("normal", corner.normal, expected.normals, expected.normal_tolerance);
      check("colour", corner.color, expected.colors, expected.color_tolerance);
    }
  }
}

void write_committed(const std::filesystem::path& path, const TriangleMesh& mesh, MeshFormat format,
                     MeshPrecision precision) {
  StagedFiles files;
  write_mesh(files, path, mesh, format, precision);
  files.commit();
}

}  // namespace clmarch::testing

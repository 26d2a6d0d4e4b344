// The octahedron and the sheet of the mesh writers' tests.
#include "support/test_meshes.hpp"

#include <cmath>

namespace clmarch::testing {

KnownMesh octahedron(const glm::dvec3& centre, double radius) {
  KnownMesh known;
  TriangleMesh& mesh = known.mesh;
  // Vertex 2 * axis is centre + radius along axis, 2 * axis + 1 the opposite one.
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      glm::dvec3 direction(0.0);
      direction[axis] = sign;
      mesh.positions.push_back(centre + radius * direction);
      mesh.normals.emplace_back(direction);
    }
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    glm::vec3 linear;
    glm::dvec3 srgb;
    for (std::size_t channel = 0; channel < 3; ++channel) {
      const SrgbPair& pair = kSrgbPairs[(i + channel) % kSrgbPairs.size()];
      linear[static_cast<int>(channel)] = pair.linear;
      srgb[static_cast<int>(channel)] = pair.srgb;
    }
    mesh.colors.push_back(linear);
    known.srgb_colors.push_back(srgb);
  }
  // The face of octant (sx, sy, sz) has corners x, y, z in that order when sx sy sz > 0 (its normal
  // cross(y - x, z - x) points outwards), else x, z, y.
  for (std::uint32_t sx = 0; sx < 2; ++sx) {
    for (std::uint32_t sy = 0; sy < 2; ++sy) {
      for (std::uint32_t sz = 0; sz < 2; ++sz) {
        const std::uint32_t x = sx, y = 2 + sy, z = 4 + sz;
        if ((sx + sy + sz) % 2 == 0) {
          mesh.triangles.push_back({x, y, z});
        } else {
          mesh.triangles.push_back({x, z, y});
        }
      }
    }
  }
  return known;
}

TriangleMesh sheet(int n) {
  TriangleMesh mesh;
  const double step = 1.0 / (n - 1);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = i * step, z = j * step;
      // y = 0.1 sin(7x) cos(5z): its normal is (-dy/dx, 1, -dy/dz), normalised.
      mesh.positions.emplace_back(x, 0.1 * std::sin(7.0 * x) * std::cos(5.0 * z), z);
      const glm::dvec3 normal(-0.7 * std::cos(7.0 * x) * std::cos(5.0 * z), 1.0,
                              0.5 * std::sin(7.0 * x) * std::sin(5.0 * z));
      mesh.normals.emplace_back(glm::normalize(normal));
      mesh.colors.emplace_back(static_cast<float>(x), 0.5f, static_cast<float>(z));
    }
  }
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * n + i); };
  // Counter-clockwise seen from +y, the side the normals face.
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
      mesh.triangles.push_back({at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
    }
  }
  return mesh;
}

}  // namespace clmarch::testing

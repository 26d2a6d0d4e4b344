// An indexed triangle mesh of a scene's surface: welded vertices with their normals and colours.
#pragma once
#include <glm/glm.hpp>
#include <array>
#include <cstdint>
#include <vector>
namespace clmarch {
/// A triangle's vertex numbers.
using MeshTriangle = std::array<std::uint32_t, 3>;

struct TriangleMesh {
  /// World positions, in double so that far-from-origin scenes keep their precision.
  std::vector<glm::dvec3> positions;
  /// Unit normals and linear RGB colours per vertex (empty, or one per position).
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> colors;
  /// Counter-clockwise seen from outside (the field's positive side).
  std::vector<MeshTriangle> triangles;
};
}  // namespace clmarch

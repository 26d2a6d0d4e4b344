// Small meshes for the mesh writers' tests, whose every value the tests know.
#pragma once

#include "mesh/triangle_mesh.hpp"

#include <array>
#include <vector>

namespace clmarch::testing {

/// A linear colour channel and its sRGB encoding, worked out apart from the code under test
/// (the sRGB curve's two pieces: 0.002 is on the linear one).
struct SrgbPair {
  float linear;
  double srgb;
};
inline constexpr std::array<SrgbPair, 6> kSrgbPairs = {
    {{0.0f, 0.0}, {1.0f, 1.0}, {0.21404114f, 0.5}, {0.05087609f, 0.25}, {0.52252155f, 0.75}, {0.002f, 0.02584}}};

/// A mesh and the sRGB encoding of each vertex's colour.
struct KnownMesh {
  TriangleMesh mesh;
  std::vector<glm::dvec3> srgb_colors;
};

/// A regular octahedron about centre: 6 vertices at centre +- radius along the axes, 8 triangles
/// counter-clockwise seen from outside, unit normals, and colours whose channels are kSrgbPairs'.
KnownMesh octahedron(const glm::dvec3& centre, double radius);

/// An n by n grid of vertices on a wavy sheet, 2 (n - 1)^2 triangles, with normals and colours:
/// a file larger than a write chunk in every format for n = 200.
TriangleMesh sheet(int n);

}  // namespace clmarch::testing

// Marching tetrahedra over the bricks of a mesh grid: each cell is split into the six tetrahedra
// of its main diagonal (Kuhn's split, the same in every cell, so the faces of neighbouring cells
// are split alike) and each tetrahedron crossed by the level set adds one or two triangles. A
// vertex is identified by the grid edge it lies on, so the mesh comes out welded, and for a closed
// surface inside the grid every edge is shared by exactly two triangles, once in each direction.
#pragma once

#include "mesh/mesh_grid.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace clmarch {

/// A vertex on a grid edge: the edge's end points below and above the level (offsets from the
/// grid's origin) with their values, and the position found on it.
struct EdgeVertex {
  glm::dvec3 below;
  glm::dvec3 above;
  float below_value = 0.0f;
  float above_value = 0.0f;
  glm::dvec3 position;
  /// Which end the last refinement step replaced: -1 below, +1 above, 0 none yet.
  int last_moved = 0;
};

class TetraSurface {
 public:
  TetraSurface(const MeshGrid& grid, double level);

  /// Adds the triangles of the brick's cells from its kBrickSamples^3 samples (x fastest, then y,
  /// then z), the vertices placed by linear interpolation along their edges.
  void add_brick(const glm::ivec3& brick, std::span<const float> samples);

  std::vector<EdgeVertex>& vertices() { return vertices_; }
  /// Counter-clockwise seen from the side above the level.
  const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return triangles_; }
  /// Cells that held part of the surface.
  std::uint64_t surface_cells() const { return surface_cells_; }

 private:
  /// The vertex on the edge from grid point low to low + step (step's bits: x 1, y 2, z 4).
  std::uint32_t vertex(const glm::ivec3& low, int step, const glm::dvec3& below, const glm::dvec3& above,
                       float below_value, float above_value);

  MeshGrid grid_;
  double level_;
  std::unordered_map<std::uint64_t, std::uint32_t> by_edge_;
  std::vector<EdgeVertex> vertices_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
  std::uint64_t surface_cells_ = 0;
};

}  // namespace clmarch

// The grid a scene is meshed on: cubic cells over the surface's bounding box, grouped in bricks of
// kBrickCells^3 cells, and the bricks the surface can cross, found by hierarchical pruning with the
// field's distance bound.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace clmarch {

class MeshField;

/// Cells along a brick's side: a brick is sampled at (kBrickCells + 1)^3 grid points.
inline constexpr int kBrickCells = 8;
inline constexpr int kBrickSamples = kBrickCells + 1;

/// Grid point (i, j, k) is at origin + (i, j, k) * cell, for 0 <= i <= cells.x and so on.
struct MeshGrid {
  glm::dvec3 origin{0.0};
  double cell = 1.0;
  glm::ivec3 cells{1};
  /// Bricks along each axis (cells rounded up to whole bricks).
  glm::ivec3 bricks{1};
};

/// The grid of resolution cells along the longest side of [low, high], grown by one cell on every
/// side so that the surface never lies on the grid's boundary.
MeshGrid mesh_grid(const glm::dvec3& low, const glm::dvec3& high, int resolution);

/// The cells along each axis that cell_key numbers: the bricks' cells (MeshGrid::bricks times
/// kBrickCells).
glm::u64vec3 cell_key_sides(const MeshGrid& grid);
/// The linear index of grid cell (x, y, z), x fastest, among cell_key_sides(grid).
std::uint64_t cell_key(const MeshGrid& grid, const glm::ivec3& cell);

/// What pruning found: the bricks left (their brick coordinates, ascending in z, y, x) and the
/// field evaluations it spent.
struct ActiveBricks {
  std::vector<glm::ivec3> bricks;
  std::uint64_t evaluations = 0;
  /// Cells of the grid inside pruned blocks.
  std::uint64_t pruned_cells = 0;
};

/// The bricks the level set field = level can cross. Blocks of bricks are tested from the coarsest
/// that covers the grid down to single bricks: a block is dropped where |field(centre) - level|
/// exceeds its half-diagonal (the field changes by at most the distance moved: its status and
/// step_factor make it a bound the march relies on too) plus half a cell of margin.
ActiveBricks find_active_bricks(const MeshGrid& grid, MeshField& field, double level);

}  // namespace clmarch

// Pruning the bricks of a mesh grid.
#include "mesh/mesh_grid.hpp"

#include "common/cancellation.hpp"
#include "mesh/mesh_field.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace clmarch {

MeshGrid mesh_grid(const glm::dvec3& low, const glm::dvec3& high, int resolution) {
  const glm::dvec3 size = high - low;
  const double longest = std::max({size.x, size.y, size.z});
  MeshGrid grid;
  grid.cell = longest / resolution;
  const glm::dvec3 centre = 0.5 * (low + high);
  for (int axis = 0; axis < 3; ++axis) {
    // One cell of margin on both sides, then whole bricks.
    const int cells = static_cast<int>(std::ceil(size[axis] / grid.cell - 1e-9)) + 2;
    grid.bricks[axis] = (cells + kBrickCells - 1) / kBrickCells;
    grid.cells[axis] = grid.bricks[axis] * kBrickCells;
    grid.origin[axis] = centre[axis] - 0.5 * grid.cells[axis] * grid.cell;
  }
  return grid;
}

ActiveBricks find_active_bricks(const MeshGrid& grid, MeshField& field, double level) {
  ActiveBricks out;
  // The coarsest block: a power of two bricks covering the longest side.
  int block = 1;
  while (block < std::max({grid.bricks.x, grid.bricks.y, grid.bricks.z})) block *= 2;
  std::vector<glm::ivec3> blocks = {glm::ivec3(0)};
  const double brick_size = kBrickCells * grid.cell;
  for (; block >= 1; block /= 2) {
    throw_if_cancelled();
    std::vector<glm::dvec3> centres;
    std::vector<glm::ivec3> inside;
    for (const glm::ivec3& b : blocks) {
      // The part of the block inside the grid.
      const glm::ivec3 end = glm::min(b + block, grid.bricks);
      if (end.x <= b.x || end.y <= b.y || end.z <= b.z) continue;
      inside.push_back(b);
      centres.push_back(0.5 * (glm::dvec3(b) + glm::dvec3(end)) * brick_size);
    }
    const std::vector<float> values = field.distances(centres);
    out.evaluations += centres.size();
    std::vector<glm::ivec3> kept;
    for (std::size_t n = 0; n < inside.size(); ++n) {
      const glm::ivec3 end = glm::min(inside[n] + block, grid.bricks);
      const double half_diagonal = 0.5 * glm::length(glm::dvec3(end - inside[n])) * brick_size;
      const double gap = std::abs(static_cast<double>(values[n]) - level);
      if (std::isfinite(gap) && gap > half_diagonal + 0.5 * grid.cell) {
        const glm::ivec3 extent = end - inside[n];
        out.pruned_cells += static_cast<std::uint64_t>(extent.x) * extent.y * extent.z *
                            static_cast<std::uint64_t>(kBrickCells * kBrickCells * kBrickCells);
        continue;
      }
      kept.push_back(inside[n]);
    }
    if (block == 1) {
      out.bricks = std::move(kept);
      break;
    }
    blocks.clear();
    const int half = block / 2;
    for (const glm::ivec3& b : kept) {
      for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
          for (int x = 0; x < 2; ++x) blocks.push_back(b + glm::ivec3(x, y, z) * half);
    }
  }
  std::sort(out.bricks.begin(), out.bricks.end(),
            [](const glm::ivec3& a, const glm::ivec3& b) { return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x); });
  return out;
}

glm::u64vec3 cell_key_sides(const MeshGrid& grid) { return glm::u64vec3(grid.bricks) * std::uint64_t{kBrickCells}; }

std::uint64_t cell_key(const MeshGrid& grid, const glm::ivec3& cell) {
  const glm::u64vec3 side = cell_key_sides(grid);
  const glm::u64vec3 c(cell);
  return (c.z * side.y + c.y) * side.x + c.x;
}

}  // namespace clmarch

// Lipschitz pruning of one large union or smooth union (after Barbier et al., "Lipschitz Pruning",
// Eurographics 2025): a grid over the operands' bounding spheres, each cell listing, in the
// scene's order, only the operands that can change the union's value inside it. Folding a cell's
// list gives the whole union's value and material at every point of the cell (up to the kernel's
// float rounding); outside the grid the union is bounded from below. The kernel side is
// kernels/operand_grid.cl; docs/performance.md has the measurements behind the settings.
#pragma once

#include "common/available_memory.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace clmarch {

/// Operands a union needs before render.pruning: auto evaluates it from a grid (measured in
/// docs/performance.md: below this the generated code builds in well under a second and its
/// steps are as cheap).
inline constexpr std::size_t kAutoGridOperands = 48;

/// Most cells of one grid: the kernel indexes them as floats, exact up to 2^24.
inline constexpr long long kMaxGridCells = 1LL << 24;

/// The pruned lists of one union.
struct OperandGrid {
  /// Corners of the grid, in the frame the union's points are given in, minus the offset.
  glm::dvec3 lower{0.0}, upper{0.0};
  double cell_size = 1.0;
  glm::ivec3 dims{1};
  /// Cell c lists operands[cell_start[c]] .. operands[cell_start[c + 1] - 1] (never empty).
  std::vector<std::uint32_t> cell_start;
  /// Indices into the union's children, ascending within a cell.
  std::vector<std::uint32_t> operands;
  /// Outside the grid the union's field is at least (distance to the grid + outside_margin) *
  /// outside_inverse_gain - outside_undershoot.
  double outside_margin = 0.0;
  double outside_inverse_gain = 1.0;
  double outside_undershoot = 0.0;

  long long cell_count() const { return static_cast<long long>(dims.x) * dims.y * dims.z; }
  /// Centre of the cell (x, y, z).
  glm::dvec3 cell_center(int x, int y, int z) const;
};

/// Whether node is a union or smooth union the grid can evaluate: at least two children, each
/// bounded (host/scene/scene_bounds.hpp).
bool grid_can_prune(const Node& node);

/// The union whose operands render.pruning evaluates from a grid, or nullptr: with auto the one
/// with the most operands among those with at least kAutoGridOperands, with grid the one with the
/// most operands, with none nothing.
const Node* grid_union(const Scene& scene);

/// Host bytes a grid of cells cells listing listed operands takes until it is packed: its cell
/// counts, starts and lists, and beside them the packed copy of the starts and lists
/// (host/codegen/sdf_codegen.cpp), 4 bytes each.
std::uint64_t grid_host_bytes(long long cells, std::uint64_t listed);

/// Builds the grid of union_node, whose points are given relative to the world point offset.
/// Reports progress on a terminal for large unions; throws Cancelled on Ctrl-C. With memory, throws
/// InputError, naming the grid and both sizes, as soon as grid_host_bytes passes memory.bytes: before
/// the cells are allocated, and while the lists grow.
OperandGrid build_operand_grid(const Node& union_node, const glm::dvec3& offset,
                               const std::optional<AvailableMemory>& memory = std::nullopt);

}  // namespace clmarch

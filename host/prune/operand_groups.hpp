// Static pruning of a small union: its bounded operands grouped by place into a hierarchy of
// bounding spheres, so that the generated map() evaluates a group only where its sphere shows it
// can change the union's value (render.subtree_bounds). A packet of points near one end of a row
// of primitives then skips the others, at the price of one sphere distance per group. Large
// unions take the operand grid instead (operand_grid.hpp).
#pragma once

#include "scene/scene_bounds.hpp"

#include <cstddef>
#include <vector>

namespace clmarch {

/// One operand of the union to group: its index among the union's children, its bound and its
/// cost in sphere evaluations (subtree cost).
struct GroupedOperand {
  std::size_t index = 0;
  BoundingSphere bounds;
  int cost = 0;
};

/// A group of operands: either a leaf holding operands or two halves, the sphere holding all of
/// them and their summed cost.
struct OperandGroup {
  std::vector<GroupedOperand> operands;  ///< a leaf's, in the order given; empty for an inner group
  std::vector<OperandGroup> halves;      ///< an inner group's two halves; empty for a leaf
  BoundingSphere bounds;
  int cost = 0;
};

/// Calls visit(operand) for every operand under group, first half first.
template <typename Visit>
void for_each_operand(const OperandGroup& group, Visit&& visit) {
  for (const OperandGroup& half : group.halves) for_each_operand(half, visit);
  for (const GroupedOperand& operand : group.operands) visit(operand);
}

/// Operands a leaf holds at most: a group of up to three primitives side by side costs about as
/// much as its bound's test saves (measured on the real-scene gallery, docs/performance.md).
inline constexpr std::size_t kLeafOperands = 3;

/// The hierarchy over operands (at least one): split at the median along the axis where their
/// centres spread most, until a group holds at most kLeafOperands.
OperandGroup group_operands(std::vector<GroupedOperand> operands);

}  // namespace clmarch

// The hierarchy of a small union's operands by place (operand_groups.hpp).
#include "prune/operand_groups.hpp"

#include <algorithm>
#include <stdexcept>

namespace clmarch {

OperandGroup group_operands(std::vector<GroupedOperand> operands) {
  if (operands.empty()) throw std::logic_error("group_operands() of no operands");
  OperandGroup group;
  group.bounds = operands.front().bounds;
  glm::dvec3 low = operands.front().bounds.center, high = low;
  for (const GroupedOperand& operand : operands) {
    group.bounds = enclosing(group.bounds, operand.bounds);
    group.cost += operand.cost;
    low = glm::min(low, operand.bounds.center);
    high = glm::max(high, operand.bounds.center);
  }
  if (operands.size() <= kLeafOperands) {
    group.operands = std::move(operands);
    return group;
  }
  const glm::dvec3 spread = high - low;
  const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
  // A stable sort keeps the scene's order among operands at the same place, so the hierarchy of a
  // scene is the same on every machine.
  std::stable_sort(operands.begin(), operands.end(), [axis](const GroupedOperand& a, const GroupedOperand& b) {
    return a.bounds.center[axis] < b.bounds.center[axis];
  });
  const auto middle = operands.begin() + static_cast<std::ptrdiff_t>(operands.size() / 2);
  group.halves.push_back(group_operands({operands.begin(), middle}));
  group.halves.push_back(group_operands({middle, operands.end()}));
  return group;
}

}  // namespace clmarch

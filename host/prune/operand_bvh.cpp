// Median-split construction of the operand BVH and its bounds.
#include "prune/operand_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace clmarch {
namespace {

/// Operands per leaf: a few sphere tests are cheaper than another level.
constexpr std::uint32_t kLeafSize = 4;

}  // namespace

double operand_lower_bound(const OperandBounds& bounds, const glm::dvec3& m, double reach) {
  const double gap = glm::length(m - bounds.center) - bounds.radius - reach;
  return gap > 0.0 ? gap / bounds.gain : -std::numeric_limits<double>::infinity();
}

OperandBvh::OperandBvh(std::vector<OperandBounds> operands) : operands_(std::move(operands)) {
  order_.resize(operands_.size());
  std::iota(order_.begin(), order_.end(), 0u);
  nodes_.reserve(2 * operands_.size() / kLeafSize + 2);
  if (!operands_.empty()) build(0, static_cast<std::uint32_t>(order_.size()));
}

std::uint32_t OperandBvh::build(std::uint32_t begin, std::uint32_t end) {
  const std::uint32_t at = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  BvhNode node;
  node.lower = glm::dvec3(std::numeric_limits<double>::infinity());
  node.upper = -node.lower;
  glm::dvec3 centre_lower = node.lower, centre_upper = node.upper;
  for (std::uint32_t k = begin; k < end; ++k) {
    const OperandBounds& b = operands_[order_[k]];
    node.lower = glm::min(node.lower, b.center - b.radius);
    node.upper = glm::max(node.upper, b.center + b.radius);
    node.gain = std::max(node.gain, b.gain);
    centre_lower = glm::min(centre_lower, b.center);
    centre_upper = glm::max(centre_upper, b.center);
  }
  if (end - begin <= kLeafSize) {
    node.first = begin;
    node.count = end - begin;
    nodes_[at] = node;
    return at;
  }
  const glm::dvec3 extent = centre_upper - centre_lower;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const std::uint32_t middle = begin + (end - begin) / 2;
  std::nth_element(
      order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
      [&](std::uint32_t a, std::uint32_t b) { return operands_[a].center[axis] < operands_[b].center[axis]; });
  // The first child follows its parent (at + 1); the second's index is kept in first.
  build(begin, middle);
  node.first = build(middle, end);
  node.count = 0;
  nodes_[at] = node;
  return at;
}

double OperandBvh::node_lower_bound(const BvhNode& node, const glm::dvec3& m, double reach) const {
  const glm::dvec3 outside = glm::max(glm::max(node.lower - m, m - node.upper), glm::dvec3(0.0));
  const double gap = glm::length(outside) - reach;
  return gap > 0.0 ? gap / node.gain : -std::numeric_limits<double>::infinity();
}

}  // namespace clmarch

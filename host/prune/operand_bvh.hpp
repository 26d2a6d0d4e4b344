// A bounding-volume hierarchy over the bounding spheres of a union's operands, for the two
// questions Lipschitz pruning asks of a ball of space (a grid cell, or a point): which operand
// has the least upper bound there, and which operands can reach below a given value there.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace clmarch {

/// An operand's field falls below tau only within radius + gain * tau of center
/// (BoundingSphere of host/scene/scene_bounds.hpp).
struct OperandBounds {
  glm::dvec3 center{0.0};
  double radius = 0.0;
  double gain = 1.0;
};

/// The least value an operand of these bounds can take in the ball of radius reach around m:
/// (|m - center| - radius - reach) / gain, or -infinity where the ball meets the bounding sphere
/// (no bound there).
double operand_lower_bound(const OperandBounds& bounds, const glm::dvec3& m, double reach);

class OperandBvh {
 public:
  explicit OperandBvh(std::vector<OperandBounds> operands);

  const std::vector<OperandBounds>& operands() const { return operands_; }

  /// Calls visit(i) for every operand i whose lower bound over the ball (m, reach) is below limit.
  template <typename Visit>
  void for_each_below(const glm::dvec3& m, double reach, double limit, Visit&& visit) const;

  /// The least upper(i) over all operands, where upper(i) bounds operand i's field over the ball
  /// (m, reach) from above; operands whose lower bound is not below the best found are skipped.
  template <typename Upper>
  double least_upper(const glm::dvec3& m, double reach, Upper&& upper) const;

 private:
  struct BvhNode {
    glm::dvec3 lower{0.0}, upper{0.0};  ///< box around the operands' spheres
    double gain = 1.0;                  ///< the largest gain below
    std::uint32_t first = 0;            ///< leaf: first index into order_; inner: the second child
    std::uint32_t count = 0;            ///< operands of a leaf; 0 for an inner node
  };

  std::uint32_t build(std::uint32_t begin, std::uint32_t end);
  double node_lower_bound(const BvhNode& node, const glm::dvec3& m, double reach) const;

  std::vector<OperandBounds> operands_;
  std::vector<std::uint32_t> order_;
  std::vector<BvhNode> nodes_;
};

template <typename Visit>
void OperandBvh::for_each_below(const glm::dvec3& m, double reach, double limit, Visit&& visit) const {
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::uint32_t at = stack[--top];
    const BvhNode& node = nodes_[at];
    if (!(node_lower_bound(node, m, reach) < limit)) continue;
    if (node.count > 0) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        if (operand_lower_bound(operands_[order_[k]], m, reach) < limit) visit(order_[k]);
      }
    } else {
      stack[top++] = at + 1;
      stack[top++] = node.first;
    }
  }
}

template <typename Upper>
double OperandBvh::least_upper(const glm::dvec3& m, double reach, Upper&& upper) const {
  double best = std::numeric_limits<double>::infinity();
  struct Pending {
    std::uint32_t at;
    double lower;
  };
  Pending stack[64];
  int top = 0;
  stack[top++] = {0, node_lower_bound(nodes_[0], m, reach)};
  while (top > 0) {
    const Pending next = stack[--top];
    if (!(next.lower < best)) continue;
    const BvhNode& node = nodes_[next.at];
    if (node.count > 0) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        if (operand_lower_bound(operands_[order_[k]], m, reach) < best) best = std::min(best, upper(order_[k]));
      }
      continue;
    }
    // The nearer child last on the stack, so it is searched first and tightens best sooner.
    const std::uint32_t a = next.at + 1, b = node.first;
    const double la = node_lower_bound(nodes_[a], m, reach), lb = node_lower_bound(nodes_[b], m, reach);
    if (la < lb) {
      stack[top++] = {b, lb};
      stack[top++] = {a, la};
    } else {
      stack[top++] = {a, la};
      stack[top++] = {b, lb};
    }
  }
  return best;
}

}  // namespace clmarch

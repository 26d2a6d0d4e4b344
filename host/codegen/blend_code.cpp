// The generated code of the blend operators: distance, color rule and skip limit.
#include "codegen/blend_code.hpp"

#include "codegen/sdf_codegen.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <type_traits>

namespace clmarch {

std::vector<std::string> blend_arguments(const Node& node, Literals& lit) {
  std::vector<std::string> args;
  std::visit(
      [&](const auto& params) {
        for_each_param(params, [&](const ParamSpec&, const auto& value) {
          if constexpr (std::is_arithmetic_v<std::decay_t<decltype(value)>>)
            args.push_back(lit.f(static_cast<double>(value)));
        });
      },
      node.params);
  return args;
}

std::string blend_distance_code(NodeKind kind, const std::string& a, const std::string& b, const std::string& args) {
  return fmt::format("op_{}({}, {}{}{})", node_kind_name(kind), a, b, args.empty() ? "" : ", ", args);
}

std::string blend_first_wins(NodeKind kind, const std::string& a, const std::string& b, const std::string& args) {
  switch (kind) {
    case NodeKind::UnionChamfer:
    case NodeKind::UnionRound:
    case NodeKind::UnionStairs:
    case NodeKind::UnionColumns:
      return fmt::format("{} <= {}", a, b);
    case NodeKind::IntersectionChamfer:
    case NodeKind::IntersectionRound:
    case NodeKind::IntersectionStairs:
    case NodeKind::IntersectionColumns:
      return fmt::format("{} >= {}", a, b);
    case NodeKind::DifferenceChamfer:
    case NodeKind::DifferenceRound:
    case NodeKind::DifferenceStairs:
    case NodeKind::DifferenceColumns:
      return fmt::format("{} >= -{}", a, b);
    // The result is +-(the operand of the least |distance|): its surface is the nearer.
    case NodeKind::Xor:
    case NodeKind::Pipe:
      return fmt::format("fabs({}) <= fabs({})", a, b);
    case NodeKind::Engrave:
      return fmt::format("{} >= engrave_cut({}, {}, {})", a, a, b, args);
    case NodeKind::Groove:
      return fmt::format("{} >= groove_cut({}, {}, {})", a, a, b, args);
    case NodeKind::Tongue:
      return fmt::format("{} <= tongue_part({}, {}, {})", a, a, b, args);
      // Every kind that is not a blend.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) case NodeKind::Kind:
#define CLMARCH_BLEND(Kind, name, min_children, params_list)
#include "scene/node_kinds.def"
      break;
  }
  throw std::logic_error("blend_first_wins() of a kind that is not a blend");
}

// Each limit L is such that b >= L makes the formula return a exactly; the kernel compares a lower
// bound of b with it, so b >= L holds wherever the child is skipped. With |b| in the formula,
// b >= L >= 0 gives |b| >= L, and a negative L holds for any |b|.
std::optional<std::string> blend_skip_limit(NodeKind kind, const std::string& acc,
                                            const std::vector<std::string>& args) {
  switch (kind) {
    // min(a, b, (a + b - r) / sqrt 2) = a once b >= a and b >= r + (sqrt 2 - 1) a; the columns'
    // field is at least the chamfer's (the columns end at a + b = r).
    case NodeKind::UnionChamfer:
    case NodeKind::UnionColumns:
      return fmt::format("fmax({}, {} + 0.41421356f * {})", acc, args[0], acc);
    // b >= r and b >= a: no fillet term, min(a, b) = a.
    case NodeKind::UnionRound:
      return fmt::format("fmax({}, {})", acc, args[0]);
    // The steps' field is at least (a + b - r) / 2 >= a once b >= a + r.
    case NodeKind::UnionStairs:
      return fmt::format("{} + {}", acc, args[0]);
    // max(a, -b, (a - b + r) / sqrt 2) = a once -b <= a and b >= r - (sqrt 2 - 1) a; the columns
    // likewise (their field is at least the chamfer's, negated).
    case NodeKind::DifferenceChamfer:
    case NodeKind::DifferenceColumns:
      return fmt::format("fmax(-{}, {} - 0.41421356f * {})", acc, args[0], acc);
    // b >= r: the second term of the fillet is 0, and -b <= -r leaves a (or max(a, -b) = a once b >= -a).
    case NodeKind::DifferenceRound:
      return fmt::format("fmax(-{}, {})", acc, args[0]);
    case NodeKind::DifferenceStairs:
      return fmt::format("{} - {}", args[0], acc);
    // b >= |a|: min(a, b) = a >= -b = -max(a, b).
    case NodeKind::Xor:
      return fmt::format("fabs({})", acc);
    // |b| >= r - (sqrt 2 - 1) a: the cut is below a.
    case NodeKind::Engrave:
      return fmt::format("{} - 0.41421356f * {}", args[0], acc);
    // |b| >= rb - a: rb - |b| <= a.
    case NodeKind::Groove:
      return fmt::format("{} - {}", args[1], acc);
    // |b| >= a + rb: the tongue's part is at least a.
    case NodeKind::Tongue:
      return fmt::format("{} + {}", acc, args[1]);
    // An intersection blend's result is the largest operand's at most: no later child can be skipped.
    case NodeKind::IntersectionChamfer:
    case NodeKind::IntersectionRound:
    case NodeKind::IntersectionStairs:
    case NodeKind::IntersectionColumns:
    case NodeKind::Pipe:
      // Every kind that is not a blend.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) case NodeKind::Kind:
#define CLMARCH_BLEND(Kind, name, min_children, params_list)
#include "scene/node_kinds.def"
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace clmarch

// The generated code of the blend operators (node_kinds.def's CLMARCH_BLEND lines, kernels/
// blend_operators.cl): their distance, which operand's material wins, and when a later child
// cannot change the result.
#pragma once

#include "scene/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace clmarch {

class Literals;

/// The blend's parameters in declaration order, as literals (the kernel's arguments after a, b).
std::vector<std::string> blend_arguments(const Node& node, Literals& lit);
/// op_<name>(a, b, args): args the arguments joined by ", " (empty for xor).
std::string blend_distance_code(NodeKind kind, const std::string& a, const std::string& b, const std::string& args);
/// The condition under which the first operand's material wins (docs/scene-format.md's colors):
/// the nearer operand for the unions, xor and pipe; the farther for the intersections; a where
/// a >= -b for the differences; a where the cut or the tongue leaves a unchanged.
std::string blend_first_wins(NodeKind kind, const std::string& a, const std::string& b, const std::string& args);
/// Above what bound of the next child the blend returns acc with acc's material (nothing: it
/// always depends on the child).
std::optional<std::string> blend_skip_limit(NodeKind kind, const std::string& acc,
                                            const std::vector<std::string>& args);

}  // namespace clmarch

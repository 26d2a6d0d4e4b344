// The blend operators (node_kinds.def's CLMARCH_BLEND lines) in double, written from their
// geometry apart from kernels/blend_operators.cl: the stairs and columns as the nearest of their
// steps and columns, the fillets case by case.
#pragma once

#include "reference/reference_sdf.hpp"

namespace clmarch {

/// The blend's distance of its left operand a and next child b, with node's parameters.
double blend_distance(const Node& node, double a, double b);
/// The same on samples, with the material of the operand that wins (docs/scene-format.md's colors).
SdfSample blend_sample(const Node& node, const SdfSample& a, const SdfSample& b);

}  // namespace clmarch

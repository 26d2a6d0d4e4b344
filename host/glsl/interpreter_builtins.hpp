// GLSL ES 3.00's built-in functions on flattened values, floats as double, by the definitions of
// the specification's chapter 8 (mod is x - y floor(x/y), fract x - floor(x), and so on).
#pragma once

#include "glsl/glsl_ir.hpp"

namespace clmarch::glsl::interpreter {

/// One argument of a built-in: its components and type.
struct Argument {
  const double* value = nullptr;
  const Type* type = nullptr;
};

/// builtin of arguments (as many as it takes), a result of type result. Component-wise functions take
/// GLSL's mixed forms: an argument of one component applies to every component (min(vec3, float)).
/// Not modf, whose out parameter the evaluator writes (modf_parts).
void apply_builtin(Builtin builtin, const Type& result, const Argument* arguments, double* out);

/// modf's parts of count components: fraction = x - trunc(x) and whole = trunc(x), both with x's sign.
void modf_parts(const double* x, int count, double* fraction, double* whole);

}  // namespace clmarch::glsl::interpreter

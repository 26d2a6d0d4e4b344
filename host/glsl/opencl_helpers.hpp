// Helper functions of an OpenCL translation, each defined once per program on first use (Scope::
// helper) and named after what it does and its GLSL argument types ("glsl0_mod_vec3_float"):
// constructors, zero values, matrix algebra, equality of aggregates, dynamic vector indexing, integer
// division without traps, and the built-ins whose GLSL definition OpenCL C lacks or reads twice.
#pragma once

#include "glsl/opencl_scope.hpp"

#include <string>
#include <vector>

namespace clmarch::glsl::opencl {

/// A matrix's column type (a vector of its rows).
Type column_type(const Type& matrix);
/// A type of `scalar` with the shape (rows, columns) of `shape`.
Type with_scalar(const Type& shape, Scalar scalar);

/// target(args...) by GLSL's constructor rules; each argument already has target's scalar type.
std::string constructor_helper(Scope& scope, const Type& target, const std::vector<Type>& args);
/// () -> the zero value of a matrix, struct or array.
std::string zero_helper(Scope& scope, const Type& type);

/// (v, i) -> v[i] for a vector type, i clamped to its components.
std::string vector_at_helper(Scope& scope, const Type& vector);
/// (v, i, x) -> v with component i (clamped) set to x.
std::string vector_with_helper(Scope& scope, const Type& vector);

/// (m, v) -> m v.
std::string matrix_times_vector_helper(Scope& scope, const Type& matrix);
/// (v, m) -> v m = transpose(m) v.
std::string vector_times_matrix_helper(Scope& scope, const Type& matrix);
/// (a, b) -> a b.
std::string matrix_times_matrix_helper(Scope& scope, const Type& a, const Type& b);
/// (a, b) -> a op b component-wise (Add, Subtract, Multiply, Divide), one of them a matrix, the
/// other a matrix of its shape or a scalar; Multiply of two matrices is matrixCompMult.
std::string matrix_componentwise_helper(Scope& scope, Operator op, const Type& a, const Type& b);
/// (m) -> -m.
std::string matrix_negate_helper(Scope& scope, const Type& matrix);
std::string transpose_helper(Scope& scope, const Type& matrix);
std::string determinant_helper(Scope& scope, const Type& matrix);
std::string inverse_helper(Scope& scope, const Type& matrix);
/// (c, r) -> c r^T.
std::string outer_product_helper(Scope& scope, const Type& column, const Type& row);

/// a == b as one bool for a and b of `type` (postfix or parenthesised operands).
std::string equal_expression(Scope& scope, const Type& type, const std::string& a, const std::string& b);

/// (a, b) -> a / b or a % b (op Divide or Modulo) of ints or uints: x / 0 and x % 0 give 0, INT_MIN
/// / -1 wraps to INT_MIN (GLSL leaves them undefined; OpenCL C would trap or be undefined).
std::string integer_divide_helper(Scope& scope, Operator op, const Type& a, const Type& b);

/// Built-ins by GLSL's definitions, each argument read once.
std::string fract_helper(Scope& scope, const Type& x);
std::string mod_helper(Scope& scope, const Type& x, const Type& y);
std::string componentwise_helper(Scope& scope, const char* function, const Type& x);
std::string step_helper(Scope& scope, const Type& edge, const Type& x);
std::string mix_helper(Scope& scope, const Type& x, const Type& a);
std::string smoothstep_helper(Scope& scope, const Type& edge, const Type& x);
std::string integer_sign_helper(Scope& scope, const Type& x);
std::string faceforward_helper(Scope& scope, const Type& n);
std::string reflect_helper(Scope& scope, const Type& i);
std::string refract_helper(Scope& scope, const Type& i);
/// (x, T* whole) -> x - trunc(x), *whole = trunc(x).
std::string modf_helper(Scope& scope, const Type& x);
/// uint(float): truncation; a negative value wraps as int(value) does, NaN gives 0, large values
/// saturate (as the interpreter does).
std::string float_to_uint_helper(Scope& scope, const Type& x);

}  // namespace clmarch::glsl::opencl

// GLSL's operators and constructors on flattened values (interpreter_program.hpp): arithmetic
// component-wise with a scalar operand applied to every component, integers wrapping at 32 bits,
// the linear-algebra products on column-major matrices.
#pragma once

#include "glsl/glsl_ir.hpp"

namespace clmarch::glsl::interpreter {

/// -value, !value or ~value (op Negate, LogicalNot or BitwiseNot) of a value of type.
void apply_unary(Operator op, const Type& type, const double* value, double* out);

/// value + 1 (increment) or value - 1 of a value of type: ++ and --.
void apply_increment(bool increment, const Type& type, const double* value, double* out);

/// left op right, a result of type result, for the binary operators but &&, || (which short-circuit)
/// and ==, != (which compare whole values, structs and arrays too: values_equal).
void apply_binary(Operator op, const Type& left_type, const double* left, const Type& right_type, const double* right,
                  const Type& result, double* out);

/// Whether apply_float_scalars computes op.
inline bool has_float_scalar_form(Operator op) {
  return op == Operator::Add || op == Operator::Subtract || op == Operator::Multiply || op == Operator::Divide ||
         op == Operator::Less || op == Operator::Greater || op == Operator::LessEqual || op == Operator::GreaterEqual;
}

/// left op right of two floats, for the operators of has_float_scalar_form: apply_binary's result
/// without its dispatch on shapes and scalar types.
inline double apply_float_scalars(Operator op, double left, double right) {
  switch (op) {
    case Operator::Add:
      return left + right;
    case Operator::Subtract:
      return left - right;
    case Operator::Multiply:
      return left * right;
    case Operator::Divide:
      return left / right;
    case Operator::Less:
      return left < right ? 1.0 : 0.0;
    case Operator::Greater:
      return left > right ? 1.0 : 0.0;
    case Operator::LessEqual:
      return left <= right ? 1.0 : 0.0;
    default:
      return left >= right ? 1.0 : 0.0;
  }
}

/// Whether two values of size doubles are equal, component by component (NaN equals nothing).
bool values_equal(const double* left, const double* right, int size);

/// The constructor of result (a scalar, vector or matrix) from one argument of type from: a scalar
/// fills a vector or a matrix's diagonal, a matrix the top-left of a matrix whose other components
/// are the identity's, anything else gives its first components; each converted to result's scalar.
void construct_from_one(const Type& result, const Type& from, const double* value, double* out);

}  // namespace clmarch::glsl::interpreter

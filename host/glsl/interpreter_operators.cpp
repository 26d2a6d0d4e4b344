// GLSL's operators and constructors on flattened values, floats as double and integers wrapping at
// 32 bits. Where GLSL leaves a result undefined, the choice made here is written beside it.
#include "glsl/interpreter_operators.hpp"

#include "glsl/interpreter_scalars.hpp"

#include <stdexcept>

namespace clmarch::glsl::interpreter {
namespace {

/// out[i] = operation(left[i], right[i]) for i < count, an operand with step 0 giving its one
/// component to each.
template <class Operation>
void componentwise(int count, const double* left, int left_step, const double* right, int right_step, double* out,
                   Operation operation) {
  for (int i = 0; i < count; ++i) out[i] = operation(left[i * left_step], right[i * right_step]);
}

/// Integer division by zero is undefined in GLSL; it gives 0 here. INT_MIN / -1 wraps to INT_MIN.
double divide_integers(Scalar scalar, double left, double right) {
  if (right == 0.0) return 0.0;
  if (scalar == Scalar::Uint) return static_cast<std::uint32_t>(left) / static_cast<std::uint32_t>(right);
  return wrap_int(static_cast<std::uint64_t>(static_cast<std::int64_t>(left) / static_cast<std::int64_t>(right)));
}

/// %: C's remainder (the dividend's sign), which GLSL ES 3.00 leaves undefined for negative
/// operands; % 0 gives 0 here.
double remainder_integers(Scalar scalar, double left, double right) {
  if (right == 0.0) return 0.0;
  if (scalar == Scalar::Uint) return static_cast<std::uint32_t>(left) % static_cast<std::uint32_t>(right);
  return wrap_int(static_cast<std::uint64_t>(static_cast<std::int64_t>(left) % static_cast<std::int64_t>(right)));
}

/// Shifts by a count past 31 (or negative) are undefined in GLSL; the count is taken modulo 32
/// here, as OpenCL C does. >> of an int is arithmetic, of a uint logical.
double shift_integer(Operator op, Scalar scalar, double value, double count) {
  const int bits = static_cast<int>(bits_of(count) & 31u);
  if (op == Operator::ShiftLeft) return wrap(scalar, bits_of(value) << bits);
  if (scalar == Scalar::Uint) return static_cast<std::uint32_t>(value) >> bits;
  return static_cast<std::int32_t>(value) >> bits;
}

void apply_float(Operator op, int count, const double* left, int left_step, const double* right, int right_step,
                 double* out) {
  switch (op) {
    case Operator::Add:
      return componentwise(count, left, left_step, right, right_step, out, [](double a, double b) { return a + b; });
    case Operator::Subtract:
      return componentwise(count, left, left_step, right, right_step, out, [](double a, double b) { return a - b; });
    case Operator::Multiply:
      return componentwise(count, left, left_step, right, right_step, out, [](double a, double b) { return a * b; });
    case Operator::Divide:
      return componentwise(count, left, left_step, right, right_step, out, [](double a, double b) { return a / b; });
    default:
      throw std::logic_error("glsl interpreter: an integer operator on floats");
  }
}

void apply_integer(Operator op, Scalar scalar, int count, const double* left, int left_step, const double* right,
                   int right_step, double* out) {
  switch (op) {
    case Operator::Add:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return wrap(scalar, bits_of(a) + bits_of(b)); });
    case Operator::Subtract:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return wrap(scalar, bits_of(a) - bits_of(b)); });
    case Operator::Multiply:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return wrap(scalar, bits_of(a) * bits_of(b)); });
    case Operator::Divide:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return divide_integers(scalar, a, b); });
    case Operator::Modulo:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return remainder_integers(scalar, a, b); });
    case Operator::ShiftLeft:
    case Operator::ShiftRight:
      return componentwise(count, left, left_step, right, right_step, out,
                           [op, scalar](double a, double b) { return shift_integer(op, scalar, a, b); });
    case Operator::BitwiseAnd:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return wrap(scalar, bits_of(a) & bits_of(b)); });
    case Operator::BitwiseOr:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return wrap(scalar, bits_of(a) | bits_of(b)); });
    case Operator::BitwiseXor:
      return componentwise(count, left, left_step, right, right_step, out,
                           [scalar](double a, double b) { return wrap(scalar, bits_of(a) ^ bits_of(b)); });
    default:
      throw std::logic_error("glsl interpreter: an operator the integers do not have");
  }
}

}  // namespace

void apply_unary(Operator op, const Type& type, const double* value, double* out) {
  const int count = type.components();
  for (int i = 0; i < count; ++i) {
    switch (op) {
      case Operator::Negate:
        out[i] = type.scalar == Scalar::Float ? -value[i] : wrap(type.scalar, 0 - bits_of(value[i]));
        break;
      case Operator::LogicalNot:
        out[i] = truth(value[i]) ? 0.0 : 1.0;
        break;
      case Operator::BitwiseNot:
        out[i] = wrap(type.scalar, ~bits_of(value[i]));
        break;
      default:
        throw std::logic_error("glsl interpreter: not a unary operator");
    }
  }
}

void apply_increment(bool increment, const Type& type, const double* value, double* out) {
  const int count = type.components();
  for (int i = 0; i < count; ++i) {
    if (type.scalar == Scalar::Float)
      out[i] = increment ? value[i] + 1.0 : value[i] - 1.0;
    else
      out[i] = wrap(type.scalar, increment ? bits_of(value[i]) + 1 : bits_of(value[i]) - 1);
  }
}

void apply_binary(Operator op, const Type& left_type, const double* left, const Type& right_type, const double* right,
                  const Type& result, double* out) {
  switch (op) {
    case Operator::MatrixTimesVector: {
      const int columns = left_type.columns, rows = left_type.rows;
      for (int r = 0; r < rows; ++r) {
        double sum = 0.0;
        for (int c = 0; c < columns; ++c) sum += left[c * rows + r] * right[c];
        out[r] = sum;
      }
      return;
    }
    case Operator::VectorTimesMatrix: {
      const int columns = right_type.columns, rows = right_type.rows;
      for (int c = 0; c < columns; ++c) {
        double sum = 0.0;
        for (int r = 0; r < rows; ++r) sum += left[r] * right[c * rows + r];
        out[c] = sum;
      }
      return;
    }
    case Operator::MatrixTimesMatrix: {
      const int rows = left_type.rows, inner = left_type.columns, columns = right_type.columns;
      for (int c = 0; c < columns; ++c)
        for (int r = 0; r < rows; ++r) {
          double sum = 0.0;
          for (int k = 0; k < inner; ++k) sum += left[k * rows + r] * right[c * inner + k];
          out[c * rows + r] = sum;
        }
      return;
    }
    case Operator::Less:
      out[0] = left[0] < right[0] ? 1.0 : 0.0;
      return;
    case Operator::Greater:
      out[0] = left[0] > right[0] ? 1.0 : 0.0;
      return;
    case Operator::LessEqual:
      out[0] = left[0] <= right[0] ? 1.0 : 0.0;
      return;
    case Operator::GreaterEqual:
      out[0] = left[0] >= right[0] ? 1.0 : 0.0;
      return;
    case Operator::LogicalXor:
      out[0] = truth(left[0]) != truth(right[0]) ? 1.0 : 0.0;
      return;
    default:
      break;
  }
  const int count = result.components();
  const int left_step = left_type.components() == 1 ? 0 : 1;
  const int right_step = right_type.components() == 1 ? 0 : 1;
  if (left_type.scalar == Scalar::Float)
    apply_float(op, count, left, left_step, right, right_step, out);
  else
    apply_integer(op, left_type.scalar, count, left, left_step, right, right_step, out);
}

bool values_equal(const double* left, const double* right, int size) {
  for (int i = 0; i < size; ++i)
    if (!(left[i] == right[i])) return false;
  return true;
}

void construct_from_one(const Type& result, const Type& from, const double* value, double* out) {
  const int count = result.components();
  if (from.components() == 1) {
    const double component = convert(value[0], from.scalar, result.scalar);
    if (!result.is_matrix()) {
      for (int i = 0; i < count; ++i) out[i] = component;
      return;
    }
    for (int c = 0; c < result.columns; ++c)
      for (int r = 0; r < result.rows; ++r) out[c * result.rows + r] = c == r ? component : 0.0;
    return;
  }
  if (from.is_matrix() && result.is_matrix()) {
    for (int c = 0; c < result.columns; ++c)
      for (int r = 0; r < result.rows; ++r)
        out[c * result.rows + r] = c < from.columns && r < from.rows
                                       ? convert(value[c * from.rows + r], from.scalar, result.scalar)
                                       : (c == r ? 1.0 : 0.0);
    return;
  }
  for (int i = 0; i < count; ++i) out[i] = convert(value[i], from.scalar, result.scalar);
}

}  // namespace clmarch::glsl::interpreter

// GLSL ES 3.00's built-in functions, floats as double. Where GLSL leaves a result undefined or up to
// the implementation, the choice made here is written beside it.
#include "glsl/interpreter_builtins.hpp"

#include "glsl/interpreter_scalars.hpp"

#include <bit>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace clmarch::glsl::interpreter {
namespace {

/// The step through an argument's components: 0 for one component given to each.
int step_of(const Argument& argument) { return argument.type->components() == 1 ? 0 : 1; }

/// out[i] = f(x[i]) over count components.
template <class F>
void map(int count, const Argument& x, double* out, F f) {
  const int step = step_of(x);
  for (int i = 0; i < count; ++i) out[i] = f(x.value[i * step]);
}

template <class F>
void map(int count, const Argument& x, const Argument& y, double* out, F f) {
  const int x_step = step_of(x), y_step = step_of(y);
  for (int i = 0; i < count; ++i) out[i] = f(x.value[i * x_step], y.value[i * y_step]);
}

template <class F>
void map(int count, const Argument& x, const Argument& y, const Argument& z, double* out, F f) {
  const int x_step = step_of(x), y_step = step_of(y), z_step = step_of(z);
  for (int i = 0; i < count; ++i) out[i] = f(x.value[i * x_step], y.value[i * y_step], z.value[i * z_step]);
}

double as_bool(bool value) { return value ? 1.0 : 0.0; }

/// round() may round halves either way in GLSL; Mesa's llvmpipe, the renders' ground truth, rounds
/// them to even, and so does this (whatever the thread's rounding mode).
double round_half_even(double x) {
  if (std::abs(x - std::trunc(x)) == 0.5) return 2.0 * std::round(x / 2.0);
  return std::round(x);
}

double clamp_value(double x, double low, double high) { return std::fmin(std::fmax(x, low), high); }

double dot_of(const double* x, const double* y, int count) {
  double sum = 0.0;
  for (int i = 0; i < count; ++i) sum += x[i] * y[i];
  return sum;
}

/// The determinant of a column-major size x size matrix, by cofactor expansion along column 0.
double determinant_of(const double* m, int size) {
  if (size == 1) return m[0];
  if (size == 2) return m[0] * m[3] - m[2] * m[1];
  double minor[9];
  double sum = 0.0;
  for (int skipped_row = 0; skipped_row < size; ++skipped_row) {
    int at = 0;
    for (int c = 1; c < size; ++c)
      for (int r = 0; r < size; ++r)
        if (r != skipped_row) minor[at++] = m[c * size + r];
    const double term = m[skipped_row] * determinant_of(minor, size - 1);
    sum += skipped_row % 2 == 0 ? term : -term;
  }
  return sum;
}

/// The inverse as the adjugate over the determinant; GLSL leaves a singular matrix's undefined
/// (here its components are infinite or NaN).
void inverse_of(const double* m, int size, double* out) {
  const double determinant = determinant_of(m, size);
  double minor[9];
  for (int column = 0; column < size; ++column)
    for (int row = 0; row < size; ++row) {
      // out(row, column) = (-1)^(row + column) det(m without row `column` and column `row`) / det.
      int at = 0;
      for (int c = 0; c < size; ++c)
        for (int r = 0; r < size; ++r)
          if (c != row && r != column) minor[at++] = m[c * size + r];
      const double cofactor = determinant_of(minor, size - 1);
      out[column * size + row] = ((row + column) % 2 == 0 ? cofactor : -cofactor) / determinant;
    }
}

void apply_geometric(Builtin builtin, const Argument* arguments, int count, double* out) {
  const double* x = arguments[0].value;
  switch (builtin) {
    case Builtin::Length:
      out[0] = std::sqrt(dot_of(x, x, count));
      return;
    case Builtin::Distance: {
      double sum = 0.0;
      for (int i = 0; i < count; ++i) sum += (x[i] - arguments[1].value[i]) * (x[i] - arguments[1].value[i]);
      out[0] = std::sqrt(sum);
      return;
    }
    case Builtin::Dot:
      out[0] = dot_of(x, arguments[1].value, count);
      return;
    case Builtin::Cross: {
      const double* y = arguments[1].value;
      out[0] = x[1] * y[2] - y[1] * x[2];
      out[1] = x[2] * y[0] - y[2] * x[0];
      out[2] = x[0] * y[1] - y[0] * x[1];
      return;
    }
    case Builtin::Normalize: {
      const double length = std::sqrt(dot_of(x, x, count));
      for (int i = 0; i < count; ++i) out[i] = x[i] / length;
      return;
    }
    case Builtin::FaceForward: {
      // faceforward(N, I, Nref): N where dot(Nref, I) < 0, else -N.
      const bool facing = dot_of(arguments[2].value, arguments[1].value, count) < 0.0;
      for (int i = 0; i < count; ++i) out[i] = facing ? x[i] : -x[i];
      return;
    }
    case Builtin::Reflect: {
      // reflect(I, N) = I - 2 dot(N, I) N.
      const double* n = arguments[1].value;
      const double d = dot_of(n, x, count);
      for (int i = 0; i < count; ++i) out[i] = x[i] - 2.0 * d * n[i];
      return;
    }
    case Builtin::Refract: {
      // refract(I, N, eta): 0 past the critical angle, else eta I - (eta dot(N, I) + sqrt(k)) N.
      const double* n = arguments[1].value;
      const double eta = arguments[2].value[0];
      const double d = dot_of(n, x, count);
      const double k = 1.0 - eta * eta * (1.0 - d * d);
      for (int i = 0; i < count; ++i) out[i] = k < 0.0 ? 0.0 : eta * x[i] - (eta * d + std::sqrt(k)) * n[i];
      return;
    }
    default:
      throw std::logic_error("glsl interpreter: not a geometric built-in");
  }
}

void apply_matrix(Builtin builtin, const Type& result, const Argument* arguments, double* out) {
  const double* m = arguments[0].value;
  const Type& type = *arguments[0].type;
  switch (builtin) {
    case Builtin::MatrixCompMult:
      for (int i = 0; i < result.components(); ++i) out[i] = m[i] * arguments[1].value[i];
      return;
    case Builtin::OuterProduct:
      // outerProduct(c, r): column vector c times row vector r, result[j][i] = c[i] r[j].
      for (int j = 0; j < result.columns; ++j)
        for (int i = 0; i < result.rows; ++i) out[j * result.rows + i] = m[i] * arguments[1].value[j];
      return;
    case Builtin::Transpose:
      for (int c = 0; c < type.columns; ++c)
        for (int r = 0; r < type.rows; ++r) out[r * type.columns + c] = m[c * type.rows + r];
      return;
    case Builtin::Determinant:
      out[0] = determinant_of(m, type.columns);
      return;
    case Builtin::Inverse:
      inverse_of(m, type.columns, out);
      return;
    default:
      throw std::logic_error("glsl interpreter: not a matrix built-in");
  }
}

}  // namespace

void modf_parts(const double* x, int count, double* fraction, double* whole) {
  for (int i = 0; i < count; ++i) fraction[i] = std::modf(x[i], &whole[i]);
}

void apply_builtin(Builtin builtin, const Type& result, const Argument* arguments, double* out) {
  const int n = result.components();
  const Argument& x = arguments[0];
  const Scalar scalar = x.type->scalar;
  switch (builtin) {
    case Builtin::Radians:
      return map(n, x, out, [](double v) { return v * (std::numbers::pi / 180.0); });
    case Builtin::Degrees:
      return map(n, x, out, [](double v) { return v * (180.0 / std::numbers::pi); });
    case Builtin::Sin:
      return map(n, x, out, [](double v) { return std::sin(v); });
    case Builtin::Cos:
      return map(n, x, out, [](double v) { return std::cos(v); });
    case Builtin::Tan:
      return map(n, x, out, [](double v) { return std::tan(v); });
    case Builtin::Asin:
      return map(n, x, out, [](double v) { return std::asin(v); });
    case Builtin::Acos:
      return map(n, x, out, [](double v) { return std::acos(v); });
    case Builtin::Atan:
      return map(n, x, out, [](double v) { return std::atan(v); });
    case Builtin::Atan2:
      return map(n, x, arguments[1], out, [](double y, double v) { return std::atan2(y, v); });
    case Builtin::Sinh:
      return map(n, x, out, [](double v) { return std::sinh(v); });
    case Builtin::Cosh:
      return map(n, x, out, [](double v) { return std::cosh(v); });
    case Builtin::Tanh:
      return map(n, x, out, [](double v) { return std::tanh(v); });
    case Builtin::Asinh:
      return map(n, x, out, [](double v) { return std::asinh(v); });
    case Builtin::Acosh:
      return map(n, x, out, [](double v) { return std::acosh(v); });
    case Builtin::Atanh:
      return map(n, x, out, [](double v) { return std::atanh(v); });
    case Builtin::Pow:
      return map(n, x, arguments[1], out, [](double v, double y) { return std::pow(v, y); });
    case Builtin::Exp:
      return map(n, x, out, [](double v) { return std::exp(v); });
    case Builtin::Log:
      return map(n, x, out, [](double v) { return std::log(v); });
    case Builtin::Exp2:
      return map(n, x, out, [](double v) { return std::exp2(v); });
    case Builtin::Log2:
      return map(n, x, out, [](double v) { return std::log2(v); });
    case Builtin::Sqrt:
      return map(n, x, out, [](double v) { return std::sqrt(v); });
    case Builtin::InverseSqrt:
      return map(n, x, out, [](double v) { return 1.0 / std::sqrt(v); });
    case Builtin::Abs:
      // abs(INT_MIN) wraps to INT_MIN.
      if (scalar == Scalar::Int) return map(n, x, out, [](double v) { return wrap_int(bits_of(std::abs(v))); });
      return map(n, x, out, [](double v) { return std::abs(v); });
    case Builtin::Sign:
      return map(n, x, out, [](double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; });
    case Builtin::Floor:
      return map(n, x, out, [](double v) { return std::floor(v); });
    case Builtin::Trunc:
      return map(n, x, out, [](double v) { return std::trunc(v); });
    case Builtin::Round:
    case Builtin::RoundEven:
      return map(n, x, out, round_half_even);
    case Builtin::Ceil:
      return map(n, x, out, [](double v) { return std::ceil(v); });
    case Builtin::Fract:
      return map(n, x, out, [](double v) { return v - std::floor(v); });
    case Builtin::Mod:
      return map(n, x, arguments[1], out, [](double v, double y) { return v - y * std::floor(v / y); });
    case Builtin::Min:
      return map(n, x, arguments[1], out, [](double v, double y) { return std::fmin(v, y); });
    case Builtin::Max:
      return map(n, x, arguments[1], out, [](double v, double y) { return std::fmax(v, y); });
    case Builtin::Clamp:
      return map(n, x, arguments[1], arguments[2], out, clamp_value);
    case Builtin::Mix:
      if (arguments[2].type->scalar == Scalar::Bool)
        return map(n, x, arguments[1], arguments[2], out,
                   [](double v, double y, double a) { return truth(a) ? y : v; });
      return map(n, x, arguments[1], arguments[2], out,
                 [](double v, double y, double a) { return v * (1.0 - a) + y * a; });
    case Builtin::Step:
      return map(n, x, arguments[1], out, [](double edge, double v) { return v < edge ? 0.0 : 1.0; });
    case Builtin::SmoothStep:
      return map(n, x, arguments[1], arguments[2], out, [](double edge0, double edge1, double v) {
        const double t = clamp_value((v - edge0) / (edge1 - edge0), 0.0, 1.0);
        return t * t * (3.0 - 2.0 * t);
      });
    case Builtin::IsNan:
      return map(n, x, out, [](double v) { return as_bool(std::isnan(v)); });
    case Builtin::IsInf:
      return map(n, x, out, [](double v) { return as_bool(std::isinf(v)); });
    // The bits of the float a GLSL float would hold: the double rounded to float first.
    case Builtin::FloatBitsToInt:
      return map(n, x, out, [](double v) { return std::bit_cast<std::int32_t>(static_cast<float>(v)); });
    case Builtin::FloatBitsToUint:
      return map(n, x, out, [](double v) { return std::bit_cast<std::uint32_t>(static_cast<float>(v)); });
    case Builtin::IntBitsToFloat:
      return map(n, x, out, [](double v) { return std::bit_cast<float>(static_cast<std::int32_t>(v)); });
    case Builtin::UintBitsToFloat:
      return map(n, x, out, [](double v) { return std::bit_cast<float>(static_cast<std::uint32_t>(v)); });
    case Builtin::Length:
    case Builtin::Distance:
    case Builtin::Dot:
    case Builtin::Cross:
    case Builtin::Normalize:
    case Builtin::FaceForward:
    case Builtin::Reflect:
    case Builtin::Refract:
      return apply_geometric(builtin, arguments, x.type->components(), out);
    case Builtin::MatrixCompMult:
    case Builtin::OuterProduct:
    case Builtin::Transpose:
    case Builtin::Determinant:
    case Builtin::Inverse:
      return apply_matrix(builtin, result, arguments, out);
    case Builtin::LessThan:
      return map(n, x, arguments[1], out, [](double v, double y) { return as_bool(v < y); });
    case Builtin::LessThanEqual:
      return map(n, x, arguments[1], out, [](double v, double y) { return as_bool(v <= y); });
    case Builtin::GreaterThan:
      return map(n, x, arguments[1], out, [](double v, double y) { return as_bool(v > y); });
    case Builtin::GreaterThanEqual:
      return map(n, x, arguments[1], out, [](double v, double y) { return as_bool(v >= y); });
    case Builtin::Equal:
      return map(n, x, arguments[1], out, [](double v, double y) { return as_bool(v == y); });
    case Builtin::NotEqual:
      return map(n, x, arguments[1], out, [](double v, double y) { return as_bool(v != y); });
    case Builtin::Any:
    case Builtin::All: {
      const bool all = builtin == Builtin::All;
      bool value = all;
      for (int i = 0; i < x.type->components(); ++i)
        value = all ? value && truth(x.value[i]) : value || truth(x.value[i]);
      out[0] = as_bool(value);
      return;
    }
    case Builtin::Not:
      return map(n, x, out, [](double v) { return as_bool(!truth(v)); });
    case Builtin::Modf:
      break;
  }
  throw std::logic_error("glsl interpreter: modf writes an out parameter: the evaluator's modf_parts");
}

}  // namespace clmarch::glsl::interpreter

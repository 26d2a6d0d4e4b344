// Scalars as the interpreter holds them: every component a double, ints, uints and bools exactly.
// Integer arithmetic runs on 64-bit patterns cut back to 32 bits, so int and uint wrap as GLSL
// ES 3.00 says; conversions between the scalar types follow its constructors.
#pragma once

#include "glsl/glsl_ir.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace clmarch::glsl::interpreter {

/// A held int or uint (or bool) as a 64-bit pattern whose low 32 bits are the GLSL value's.
inline std::uint64_t bits_of(double value) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(value)); }

/// The low 32 bits of bits as the held value of an int or of a uint.
inline double wrap_int(std::uint64_t bits) { return static_cast<std::int32_t>(static_cast<std::uint32_t>(bits)); }
inline double wrap_uint(std::uint64_t bits) { return static_cast<std::uint32_t>(bits); }
inline double wrap(Scalar scalar, std::uint64_t bits) {
  return scalar == Scalar::Uint ? wrap_uint(bits) : wrap_int(bits);
}

/// A bool's value: any non-zero component is true.
inline bool truth(double value) { return value != 0.0; }

/// float to int truncates toward zero. GLSL leaves NaN and values out of int's range undefined:
/// NaN gives 0 and the others saturate (OpenCL's convert_int_sat_rtz).
inline double float_to_int(double value) {
  if (std::isnan(value)) return 0.0;
  return std::clamp(std::trunc(value), -2147483648.0, 2147483647.0);
}

/// float to uint truncates toward zero. Undefined in GLSL for negative values and NaN: a negative
/// value wraps as int(value) does converted to uint (uint(-1.0) = 4294967295), NaN gives 0, values
/// past uint's range saturate.
inline double float_to_uint(double value) {
  if (value < 0.0) return wrap_uint(bits_of(float_to_int(value)));
  if (std::isnan(value)) return 0.0;
  return std::min(std::trunc(value), 4294967295.0);
}

/// value, held as from's scalar, converted to to's as a constructor converts it.
inline double convert(double value, Scalar from, Scalar to) {
  if (from == to) return value;
  switch (to) {
    case Scalar::Bool:
      return truth(value) ? 1.0 : 0.0;
    case Scalar::Int:
      return from == Scalar::Float ? float_to_int(value) : wrap_int(bits_of(value));
    case Scalar::Uint:
      return from == Scalar::Float ? float_to_uint(value) : wrap_uint(bits_of(value));
    case Scalar::Float:
    case Scalar::Void:
      break;
  }
  return value;
}

}  // namespace clmarch::glsl::interpreter

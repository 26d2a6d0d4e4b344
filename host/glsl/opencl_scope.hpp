// The program scope of one OpenCL translation: the names it defines (each prefixed, none twice), the
// C spelling of GLSL types and constants, and the typedefs and helper functions it defines on
// demand, each once, in an order where a definition follows what it uses.
#pragma once

#include "glsl/glsl_ir.hpp"
#include "glsl/opencl_translation.hpp"

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace clmarch::glsl::opencl {

/// C's operator precedence, higher binding tighter: an operand whose precedence is lower than its
/// place wants is parenthesised.
enum Precedence : int {
  kComma = 1,
  kAssignment = 2,
  kConditional = 3,
  kLogicalOr = 4,
  kLogicalAnd = 5,
  kBitOr = 6,
  kBitXor = 7,
  kBitAnd = 8,
  kEquality = 9,
  kRelational = 10,
  kShift = 11,
  kAdditive = 12,
  kMultiplicative = 13,
  kUnary = 15,
  kPostfix = 16,
};

/// text, in parentheses when its precedence is below `wanted`.
std::string parenthesised(const std::string& text, int precedence, int wanted);

/// -text, parenthesised where text is not a primary (and never "--").
std::string negated(const std::string& text, int precedence);

/// A scalar or a vector that is not an array (Type::is_scalar and is_vector hold for arrays of them).
inline bool is_single_scalar(const Type& type) { return type.is_scalar() && !type.is_array(); }
inline bool is_single_vector(const Type& type) { return type.is_vector() && !type.is_array(); }

/// The component letter of index 0-3 (x, y, z, w).
char component_letter(int index);

/// OpenCL C's function for a GLSL built-in that means the same, component by component, on floats
/// (sin, floor, rsqrt for inversesqrt, rint for round, min, ...); nullptr for the others, which
/// need a form of their own (mod, fract, mix, step, pow and atan2 of vectors, integer forms, ...).
const char* same_opencl_function(Builtin builtin);

/// C's symbol for a GLSL operator of two operands that C spells alike (+ - * / % << >> & | ^, the
/// comparisons); throws std::logic_error for the others.
const char* c_symbol(Operator op);

/// Names, types, constants and helpers at program scope.
class Scope {
 public:
  Scope(const Module& module, const TranslationOptions& options);

  const Module& module() const { return module_; }
  const TranslationOptions& options() const { return options_; }

  /// "<prefix>_<wanted>", numbered ("_2", "_3") where another definition took it; reserved.
  std::string unique_name(const std::string& wanted);

  /// The C type of a GLSL type: float/double and their vectors, int, uint, bool, intN for bvecN,
  /// typedef'd structs for matrices (columns c[]), user structs and arrays (elements e[]).
  std::string type(const Type& type);
  /// A GLSL-like word for a type in helper names: "vec3", "mat2x3", "ivec2", "Hit", "float_array4".
  std::string glsl_name(const Type& type) const;
  /// float or double.
  std::string real() const { return options_.double_precision ? "double" : "float"; }
  /// The C member name of a user struct's member.
  std::string member_name(const Type& struct_type, int member) const;

  /// A scalar constant of the scalar type: float constants exact for the precision (0.5f; 17
  /// significant digits for double at most), ints that never overflow a literal.
  std::string scalar_literal(double value, Scalar scalar) const;
  /// A whole constant of a type from its flattened components (Expr::constant); sets precedence.
  std::string constant(const Type& type, const double* components, int* precedence);
  /// The zero value of a type (what uninitialised locals hold).
  std::string zero(const Type& type);
  /// Scalar components a value of the type holds (flattened as Expr::constant).
  int flattened_size(const Type& type) const;

  /// The name of the helper `wanted` (a key as well as the name wanted), defining it with
  /// define(name) the first time; definitions the body asks for come before it.
  std::string helper(const std::string& wanted, const std::function<std::string(const std::string&)>& define);

  /// The typedefs and helpers defined so far, in order.
  const std::vector<std::string>& definitions() const { return definitions_; }

 private:
  std::string define_aggregate(const Type& type);

  const Module& module_;
  const TranslationOptions& options_;
  std::set<std::string> taken_;
  std::map<std::string, std::string> helpers_;
  std::map<std::string, std::string> aggregate_names_;
  std::vector<std::string> definitions_;
};

}  // namespace clmarch::glsl::opencl

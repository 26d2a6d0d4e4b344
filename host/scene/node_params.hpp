// The parameters of every node kind, generated from the declarations in scene/node_kinds.def: one
// struct per kind, the NodeParams variant (its alternatives in the list's order, so the index of
// a node's parameters is its NodeKind), and for_each_param, which walks a struct's parameters in
// declaration order with their keys and ranges (the loader, the code generator and the docs test
// read the table through it).
#pragma once

#include "scene/glsl_program.hpp"
#include "scene/value_range.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <variant>

namespace clmarch {

/// The noise a terrain's fractal sum is built from (formulas: kernels/noise.cl, reference_noise.cpp).
enum class TerrainNoise { Value, Perlin, Derivative };
inline constexpr const char* kTerrainNoiseNames[] = {"value", "perlin", "derivative"};

/// How a primitive's field relates to the true signed distance.
enum class FieldQuality {
  /// The exact signed Euclidean distance.
  Exact,
  /// A lower bound of it that changes by at most the distance moved (1-Lipschitz).
  Bound,
  /// Neither: steeper than 1 in places (an escape-time estimate, a height field); a bound only
  /// with a node step_factor.
  Estimate,
};
inline constexpr const char* kFieldQualityNames[] = {"exact", "bound", "estimate"};

/// The kind of value a parameter holds, which decides how it is read, checked and passed.
enum class ParamType {
  /// A position in the node's frame (moves with the map frame's origin).
  Point,
  /// A vector of sizes or periods, each component in the range.
  Vector,
  /// A non-zero vector, unit length after loading.
  Direction,
  Scalar,
  /// An integer; the generated code holds it as a literal (a change makes another program).
  Integer,
  /// One of a list of names; like an integer, part of the generated code.
  Choice,
  /// A non-empty set of the axes x, y, z, written as a list of their names.
  Axes,
  /// Three integers.
  IntegerVector,
  /// Four numbers (a quaternion), each in the range.
  Vector4,
  /// User GLSL: a glsl node's program, read from several keys (scene/glsl_program.hpp).
  Program,
};

/// One row of a kind's parameter table.
struct ParamSpec {
  const char* key;
  ParamType type;
  Range range;
  /// A scene file must give it (it has no default).
  bool required = false;
  /// The names of a Choice, in the order of its enum.
  std::span<const char* const> choices = {};
};

// Commas only inside parentheses, so that CLMARCH_PROFILE and CLMARCH_MODIFIER can pass a
// parameter list on to CLMARCH_PRIMITIVE and CLMARCH_OPERATOR as one argument.
#define CLMARCH_POINT(member, x, y, z) glm::dvec3 member = glm::dvec3(x, y, z);
#define CLMARCH_VECTOR(member, x, y, z, range) glm::dvec3 member = glm::dvec3(x, y, z);
#define CLMARCH_VECTOR4(member, x, y, z, w, range) glm::dvec4 member = glm::dvec4(x, y, z, w);
#define CLMARCH_DIRECTION(member, x, y, z) glm::dvec3 member = glm::dvec3(x, y, z);
#define CLMARCH_SCALAR(member, value, range) double member = value;
#define CLMARCH_INTEGER(member, type, value, low, high) type member = value;
#define CLMARCH_CHOICE(member, Enum, value, names) Enum member = Enum::value;
#define CLMARCH_REQUIRED_SCALAR(member, range) double member = 0.0;
#define CLMARCH_REQUIRED_VECTOR(member, range) glm::dvec3 member{0.0};
#define CLMARCH_REQUIRED_INTEGER(member, low, high) int member = 0;
#define CLMARCH_REQUIRED_INTEGERS(member, low, high) glm::ivec3 member{0};
#define CLMARCH_REQUIRED_AXES(member) glm::bvec3 member{false};
#define CLMARCH_GLSL_PROGRAM(member) std::shared_ptr<const GlslProgram> member = default_glsl_program();
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params) \
  struct Kind {                                              \
    params                                                   \
  };
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params) \
  struct Kind {                                                          \
    params                                                               \
  };
// node_kinds.def undefines the parameter macros at its end: the visits below define them anew.
#include "scene/node_kinds.def"

/// Drops the void that closes a list generated with a comma after every entry.
template <class... Types>
struct TypeList {};
template <class List, class... Kept>
struct VariantBeforeVoid;
template <class... Kept>
struct VariantBeforeVoid<TypeList<void>, Kept...> {
  using type = std::variant<Kept...>;
};
template <class Head, class... Tail, class... Kept>
struct VariantBeforeVoid<TypeList<Head, Tail...>, Kept...> : VariantBeforeVoid<TypeList<Tail...>, Kept..., Head> {};

/// The parameters of a node, the alternative at the index of its NodeKind.
using NodeParams = VariantBeforeVoid<TypeList<
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params) Kind,
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params) Kind,
#include "scene/node_kinds.def"
    void>>::type;

// for_each_param(params, visit): visit(const ParamSpec&, member&) for each parameter, in order.
#define CLMARCH_POINT(member, x, y, z) visit(ParamSpec{#member, ParamType::Point, Range::any()}, params.member);
#define CLMARCH_VECTOR(member, x, y, z, range) visit(ParamSpec{#member, ParamType::Vector, range}, params.member);
#define CLMARCH_VECTOR4(member, x, y, z, w, range) visit(ParamSpec{#member, ParamType::Vector4, range}, params.member);
#define CLMARCH_DIRECTION(member, x, y, z) visit(ParamSpec{#member, ParamType::Direction, Range::any()}, params.member);
#define CLMARCH_SCALAR(member, value, range) visit(ParamSpec{#member, ParamType::Scalar, range}, params.member);
#define CLMARCH_INTEGER(member, type, value, low, high) \
  visit(ParamSpec{#member, ParamType::Integer, Range::closed(low, high)}, params.member);
#define CLMARCH_CHOICE(member, Enum, value, names) \
  visit(ParamSpec{#member, ParamType::Choice, Range::any(), false, names}, params.member);
#define CLMARCH_REQUIRED_SCALAR(member, range) visit(ParamSpec{#member, ParamType::Scalar, range, true}, params.member);
#define CLMARCH_REQUIRED_VECTOR(member, range) visit(ParamSpec{#member, ParamType::Vector, range, true}, params.member);
#define CLMARCH_REQUIRED_INTEGER(member, low, high) \
  visit(ParamSpec{#member, ParamType::Integer, Range::closed(low, high), true}, params.member);
#define CLMARCH_REQUIRED_INTEGERS(member, low, high) \
  visit(ParamSpec{#member, ParamType::IntegerVector, Range::closed(low, high), true}, params.member);
#define CLMARCH_REQUIRED_AXES(member) visit(ParamSpec{#member, ParamType::Axes, Range::any(), true}, params.member);
#define CLMARCH_GLSL_PROGRAM(member) visit(ParamSpec{#member, ParamType::Program, Range::any()}, params.member);
// Kind names a type here, which parentheses would break.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define CLMARCH_KIND_PARAMS(Kind, params_list)                                               \
  template <class Visit>                                                                     \
  void for_each_param([[maybe_unused]] Kind& params, [[maybe_unused]] Visit&& visit) {       \
    params_list                                                                              \
  }                                                                                          \
  template <class Visit>                                                                     \
  void for_each_param([[maybe_unused]] const Kind& params, [[maybe_unused]] Visit&& visit) { \
    params_list                                                                              \
  }
// NOLINTEND(bugprone-macro-parentheses)
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params) CLMARCH_KIND_PARAMS(Kind, params)
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params) CLMARCH_KIND_PARAMS(Kind, params)
#include "scene/node_kinds.def"
#undef CLMARCH_KIND_PARAMS

/// Whether a parameter struct is a primitive's.
template <class Params>
inline constexpr bool kIsPrimitiveParams = false;
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) \
  template <>                                                     \
  inline constexpr bool kIsPrimitiveParams<Kind> = true;
#include "scene/node_kinds.def"

}  // namespace clmarch

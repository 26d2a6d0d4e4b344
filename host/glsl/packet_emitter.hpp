// The packet translation's emitter (opencl_packets.hpp): one function of the user's code at a
// time as packet code. Each GLSL value is a list of component texts: a float, vector or matrix one
// text per component (column-major), each of type vfloat, or `real` where it does not depend on the
// point (a constant, iTime); an int or bool one C scalar. Results of arithmetic are bound to
// `const vfloat` temporaries as they are made, so every text is a name or a literal and may be read
// any number of times; the compiler folds the copies. Statements are in packet_statements.cpp,
// expressions in packet_expressions.cpp, built-in functions in packet_builtins.cpp.
#pragma once

#include "glsl/glsl_ir.hpp"
#include "glsl/opencl_emitter.hpp"
#include "glsl/opencl_scope.hpp"

#include <fmt/format.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace clmarch::glsl::packets {

using opencl::is_single_scalar;
using opencl::Lines;
using opencl::Scope;
using opencl::Writer;

/// Thrown where the module leaves the packet subset; the caller keeps the lane-at-a-time path.
struct Unsupported {
  std::string reason;
};

[[noreturn]] inline void unsupported(const SourceLocation& at, const std::string& what) {
  throw Unsupported{fmt::format("line {}: {}", at.line, what)};
}

/// Floats, vectors and matrices of floats: one lane vector per component.
inline bool is_real(const Type& type) { return type.scalar == Scalar::Float && !type.is_struct() && !type.is_array(); }

/// Ints, uints and bools that are not vectors: C scalars, the same on every lane.
inline bool is_uniform_scalar(const Type& type) {
  return (type.scalar == Scalar::Int || type.scalar == Scalar::Uint || type.scalar == Scalar::Bool) &&
         is_single_scalar(type);
}

/// What a value's texts are.
enum class Kind {
  /// C scalars the same on every lane: constants, iTime, loop counters (real, int, uint or bool).
  Uniform,
  /// vfloat per component.
  Packet,
  /// A bool per lane, as a vint mask (-1 true, 0 false): a comparison of packet values.
  Mask,
};

struct PacketValue {
  std::vector<std::string> c;
  Kind kind = Kind::Uniform;
  /// Every text is a temporary or a literal: a later write to a variable cannot change it.
  bool stable = true;
};

inline bool is_increment(Operator op) {
  return op == Operator::PreIncrement || op == Operator::PreDecrement || op == Operator::PostIncrement ||
         op == Operator::PostDecrement;
}

/// What statements write and declare, and the first one that leaves them.
struct Writes {
  /// Variables written: roots of assignments, increments and out arguments, and the globals the
  /// functions called write.
  std::set<int> written;
  std::set<int> declared;
  /// A return, or a break or continue outside the statements' own loops and switches.
  const Stmt* leaves = nullptr;
};

/// Adds what stmt writes and declares to writes. globals_written: per function, the globals it and
/// its callees write (those of the functions stmt calls must be there). loops and breakables: the
/// loops, and the loops and switches, around stmt inside the statements collected.
void collect_writes(const Module& module, const std::vector<std::set<int>>& globals_written, const Stmt& stmt,
                    Writes& writes, int loops = 0, int breakables = 0);

/// What the whole module tells each function's translation.
struct ModuleInfo {
  /// Per function: its C name, its C return type, and the globals it or its callees write.
  std::vector<std::string> names;
  std::vector<std::string> return_types;
  std::vector<std::set<int>> globals_written;
  /// The C struct of the shader's globals, which every function gets by pointer (`globals`);
  /// empty where the module has none.
  std::string globals_type;
};

/// One function's body as packet code.
class PacketEmitter {
 public:
  PacketEmitter(Scope& scope, const ModuleInfo& info) : scope_(scope), module_(scope.module()), info_(info) {}

  void function(int index, Writer& out);
  /// Statements giving the globals (through `globals`) their initial values, as every call of an
  /// entry point does.
  void global_initialisers(Writer& out);

 private:
  // Statements.
  void statement(const Stmt& stmt, Writer& out);
  void loop(const Stmt& stmt, Writer& out);
  void declaration(const Stmt& stmt, Writer& out);
  void masked_if(const Stmt& stmt, const std::string& mask, Writer& out);
  void masked_branch(const Stmt& body, const std::vector<int>& written, const std::string& mask, Writer& out);

  // Expressions.
  PacketValue emit(const Expr& expr, Lines& pre);
  PacketValue variable(const Expr& expr);
  PacketValue operation(const Expr& expr, Lines& pre);
  PacketValue arithmetic(Operator op, const Type& result, const PacketValue& a, const PacketValue& b, Lines& pre);
  PacketValue compare(const Expr& expr, const PacketValue& a, const PacketValue& b, Lines& pre);
  PacketValue logical(const Expr& expr, Lines& pre);
  PacketValue select(const Expr& expr, Lines& pre);
  PacketValue assignment(const Expr& expr, Lines& pre);
  PacketValue increment(const Expr& expr, Lines& pre);
  PacketValue construct(const Expr& expr, Lines& pre);
  PacketValue call(const Expr& expr, Lines& pre);
  PacketValue builtin(const Expr& expr, Lines& pre);
  PacketValue products(const Expr& expr, const PacketValue& a, const PacketValue& b, Lines& pre);
  /// The operands in order, each read before a later one's side effects.
  std::vector<PacketValue> in_order(const std::vector<Expr>& operands, Lines& pre);
  /// The places an lvalue names, one per component.
  std::vector<std::string> places(const Expr& expr);
  /// Writes a value (not a mask: callers refuse those) to the places.
  void store(const std::vector<std::string>& places, const Type& type, PacketValue value, Lines& pre);

  /// Binds each component to a temporary (packet and mask values); uniform texts are kept.
  PacketValue bound(PacketValue value, Lines& pre);
  PacketValue stabilised(PacketValue value, const Type& type, Lines& pre);
  std::string temporary(const std::string& type, const std::string& text, Lines& pre);
  /// A component text as a vfloat (uniform ones broadcast).
  static std::string packet(const PacketValue& value, size_t i);
  /// Component i of a value, a scalar value giving its one component for every i.
  static const std::string& component(const PacketValue& value, size_t i) {
    return value.c.size() == 1 ? value.c[0] : value.c[i];
  }
  std::string literal(double value) const { return scope_.scalar_literal(value, Scalar::Float); }
  std::string c_scalar(Scalar scalar) const { return scalar == Scalar::Uint ? "uint" : "int"; }
  std::string name_of(int variable);
  std::string component_name(int variable, int i);
  bool has_effects(const Expr& expr) const;

  Scope& scope_;
  const Module& module_;
  const ModuleInfo& info_;
  std::map<int, std::string> local_names_;
  std::vector<std::string> used_names_;
  std::vector<bool> out_parameter_ = std::vector<bool>(module_.variables.size(), false);
  const Function* function_ = nullptr;
  int function_index_ = -1;
  int temporaries_ = 0;
  int loops_ = 0;
};

}  // namespace clmarch::glsl::packets

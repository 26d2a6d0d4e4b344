// Runs one call of a compiled Program's entry point: evaluates its expressions and executes its
// statements on a frame of doubles the caller provides, so that calls on different frames (on
// different threads) share nothing.
#pragma once

#include "glsl/glsl_uniforms.hpp"
#include "glsl/interpreter_program.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace clmarch::glsl::interpreter {

/// Where an lvalue's components are: size doubles from data, or where swizzled data[map[i]].
struct Place {
  double* data = nullptr;
  int size = 0;
  bool swizzled = false;
  std::array<std::int8_t, 4> map{};
};

/// to[i] = from[i] for i < count; from and to are the same value or apart. A plain loop: most
/// values are 1 to 4 doubles, for which memmove's call cost more than the copy (5% of the time).
inline void copy_values(const double* from, int count, double* to) {
  for (int i = 0; i < count; ++i) to[i] = from[i];
}

/// Loop iterations one call of an entry point may run, all loops together, before it is taken for
/// a runaway loop (an InputError rather than a reference render that never ends).
inline constexpr std::uint64_t kMaxLoopIterations = std::uint64_t{1} << 24;

/// One call of an entry point.
class Evaluator {
 public:
  /// frame: Program::frame_size doubles, places: Program::place_count places, both the call's own.
  Evaluator(const Program& program, double* frame, Place* places);

  /// Sets the uniforms, initialises the globals and runs function (an entry point) with p as its
  /// first parameter; returns its result's components, valid until the frame is used again.
  const double* run(int function, const double* p, double time, const UniformValues& uniforms);

 private:
  /// How a statement ends.
  enum class Flow { Next, Break, Continue, Return };

  void set_uniforms(double time, const UniformValues& uniforms);
  Flow execute(const Statement& statement);
  Flow execute_from(const std::vector<Statement>& body, std::size_t first);
  Flow loop(const Statement& statement);
  Flow switch_cases(const Statement& statement);

  /// The node's value: a pointer into the frame (a variable's storage, the node's slot) or to a
  /// constant, valid until something writes there; evaluate_operands keeps operands apart. The
  /// leaves, most of a tree's nodes, inline: a call and a switch fewer (a third of the time).
  const double* evaluate(const Node& node) {
    if (node.kind == ExprKind::Variable) return frame_ + node.variable_offset;
    if (node.kind == ExprKind::Constant) return node.constant.data();
    return evaluate_inner(node);
  }
  const double* evaluate_inner(const Node& node);
  void evaluate_operands(const Node& node, const double** values);
  Place locate(const Node& node);
  const double* operation(const Node& node);
  const double* increment(const Node& node);
  const double* assign(const Node& node);
  const double* construct(const Node& node);
  const double* call(const Node& node);
  const double* builtin(const Node& node);

  const Program& program_;
  double* frame_;
  Place* places_;
  /// The value of the last return statement run (nullptr for a bare return).
  const double* return_value_ = nullptr;
  std::uint64_t loop_iterations_ = 0;
};

}  // namespace clmarch::glsl::interpreter

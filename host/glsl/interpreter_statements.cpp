// The Evaluator's statements and its entry: uniforms set and globals initialised at the start of
// every call, locals zeroed where declared without an initializer (as WebGL does), loops counted so
// that a runaway one ends the call with an InputError.
#include "glsl/interpreter_evaluator.hpp"

#include "common/errors.hpp"
#include "glsl/interpreter_scalars.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace clmarch::glsl::interpreter {

Evaluator::Evaluator(const Program& program, double* frame, Place* places)
    : program_(program), frame_(frame), places_(places) {}

const double* Evaluator::run(int function, const double* p, double time, const UniformValues& uniforms) {
  set_uniforms(time, uniforms);
  for (const Statement& global : program_.globals) execute(global);
  const CompiledFunction& entry = program_.functions.at(function);
  copy_values(p, 3, frame_ + entry.parameters[0].offset);
  // A result nowhere returned (the function's end reached) reads as zeros.
  static constexpr double kNoResult[4] = {};
  if (execute(entry.body) != Flow::Return || return_value_ == nullptr) return kNoResult;
  return return_value_;
}

void Evaluator::set_uniforms(double time, const UniformValues& uniforms) {
  for (const UniformSlot& uniform : program_.uniforms) {
    double value[4] = {};
    switch (uniform.kind) {
      case UniformKind::Time:
        value[0] = time;
        break;
      case UniformKind::Resolution:
        value[0] = uniforms.resolution_x;
        value[1] = uniforms.resolution_y;
        value[2] = 1.0;
        break;
      case UniformKind::Frame:
        value[0] = frame_at(time);
        break;
      case UniformKind::TimeDelta:
        value[0] = 1.0 / kFramesPerSecond;
        break;
      case UniformKind::Mouse:
      case UniformKind::None:
        break;
    }
    for (int i = 0; i < uniform.size; ++i) frame_[uniform.offset + i] = i < 4 ? value[i] : 0.0;
  }
}

Evaluator::Flow Evaluator::execute(const Statement& statement) {
  switch (statement.kind) {
    case StmtKind::Expression:
      evaluate(statement.expression);
      return Flow::Next;
    case StmtKind::Declaration: {
      double* variable = frame_ + statement.variable_offset;
      if (statement.has_value)
        copy_values(evaluate(statement.expression), statement.variable_size, variable);
      else
        std::fill_n(variable, statement.variable_size, 0.0);
      return Flow::Next;
    }
    case StmtKind::Block:
      return execute_from(statement.body, 0);
    case StmtKind::If:
      if (truth(evaluate(statement.expression)[0])) return execute(statement.body[0]);
      return statement.body.size() > 1 ? execute(statement.body[1]) : Flow::Next;
    case StmtKind::Loop:
      return loop(statement);
    case StmtKind::Switch:
      return switch_cases(statement);
    case StmtKind::Case:
      return Flow::Next;
    case StmtKind::Return:
      return_value_ = statement.has_value ? evaluate(statement.expression) : nullptr;
      return Flow::Return;
    case StmtKind::Break:
      return Flow::Break;
    case StmtKind::Continue:
      return Flow::Continue;
  }
  return Flow::Next;
}

Evaluator::Flow Evaluator::execute_from(const std::vector<Statement>& body, std::size_t first) {
  for (std::size_t index = first; index < body.size(); ++index) {
    const Flow flow = execute(body[index]);
    if (flow != Flow::Next) return flow;
  }
  return Flow::Next;
}

Evaluator::Flow Evaluator::loop(const Statement& statement) {
  for (bool first = true;; first = false) {
    // A do-while loop tests its condition after the body: from the second iteration on.
    if ((statement.test_first || !first) && statement.has_condition && !truth(evaluate(statement.expression)[0]))
      return Flow::Next;
    if (++loop_iterations_ > kMaxLoopIterations)
      throw InputError(fmt::format(
          "{}:{}:{}: this loop ran past {} iterations in one evaluation of the distance or colour function; "
          "the CPU reference takes it for an endless loop",
          program_.file_name, statement.location.line, statement.location.column, kMaxLoopIterations));
    const Flow flow = execute(statement.body[0]);
    if (flow == Flow::Break) return Flow::Next;
    if (flow == Flow::Return) return Flow::Return;
    if (statement.has_step) evaluate(statement.step);
  }
}

Evaluator::Flow Evaluator::switch_cases(const Statement& statement) {
  const double value = evaluate(statement.expression)[0];
  int start = statement.default_case;
  for (const auto& [label, index] : statement.cases)
    if (label == value) {
      start = index;
      break;
    }
  if (start < 0) return Flow::Next;
  for (const auto& [offset, size] : statement.body_variables) std::fill_n(frame_ + offset, size, 0.0);
  // Cases fall through to the next until a break, which ends the switch (a continue, the loop's).
  const Flow flow = execute_from(statement.body, start);
  return flow == Flow::Break ? Flow::Next : flow;
}

}  // namespace clmarch::glsl::interpreter

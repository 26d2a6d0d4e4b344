// The Evaluator's expressions, left to right as GLSL orders them: lvalues located once, out and
// inout arguments copied in at the call and out after it, && || and ?: evaluating only what they
// need. Values stay where they are (a variable's storage, a node's slot) unless a later side effect
// could change them first.
#include "glsl/interpreter_evaluator.hpp"

#include "glsl/interpreter_builtins.hpp"
#include "glsl/interpreter_operators.hpp"
#include "glsl/interpreter_scalars.hpp"

#include <algorithm>
#include <stdexcept>

namespace clmarch::glsl::interpreter {
namespace {

/// The element an index selects. GLSL leaves an index out of range undefined (a constant one does
/// not compile); it is clamped to the range here, so that it reads and writes the nearest element
/// rather than memory outside the value.
int element_index(const Node& node, double index) {
  return static_cast<int>(std::clamp(index, 0.0, static_cast<double>(node.element_count - 1)));
}

/// The components at place: its data where contiguous, else gathered into buffer (4 doubles).
const double* read(const Place& place, double* buffer) {
  if (!place.swizzled) return place.data;
  for (int i = 0; i < place.size; ++i) buffer[i] = place.data[place.map[i]];
  return buffer;
}

void write(const Place& place, const double* value) {
  if (!place.swizzled) {
    copy_values(value, place.size, place.data);
    return;
  }
  // value may be the same vector's storage (`v.yx = v`): copied before any component is written.
  double copy[4];
  copy_values(value, place.size, copy);
  for (int i = 0; i < place.size; ++i) place.data[place.map[i]] = copy[i];
}

}  // namespace

const double* Evaluator::evaluate_inner(const Node& node) {
  switch (node.kind) {
    case ExprKind::Constant:
      return node.constant.data();
    case ExprKind::Variable:
      return frame_ + node.variable_offset;
    case ExprKind::Swizzle: {
      const double* value = evaluate(node.operands[0]);
      double* out = frame_ + node.slot;
      for (int i = 0; i < node.size; ++i) out[i] = value[node.components[i]];
      return out;
    }
    case ExprKind::Index: {
      const double* values[2];
      evaluate_operands(node, values);
      return values[0] + element_index(node, values[1][0]) * node.element_size;
    }
    case ExprKind::Member:
      return evaluate(node.operands[0]) + node.member_offset;
    case ExprKind::Operation:
      return operation(node);
    case ExprKind::Assign:
      return assign(node);
    case ExprKind::Select:
      return evaluate(node.operands[truth(evaluate(node.operands[0])[0]) ? 1 : 2]);
    case ExprKind::Comma: {
      const double* value = nullptr;
      for (const Node& operand : node.operands) value = evaluate(operand);
      return value;
    }
    case ExprKind::Construct:
      return construct(node);
    case ExprKind::Call:
      return call(node);
    case ExprKind::BuiltinCall:
      return builtin(node);
  }
  throw std::logic_error("glsl interpreter: an unknown expression kind");
}

void Evaluator::evaluate_operands(const Node& node, const double** values) {
  double* copies = node.protects_operands ? frame_ + node.scratch : nullptr;
  const std::size_t last = node.operands.size() - 1;
  for (std::size_t k = 0; k <= last; ++k) {
    values[k] = evaluate(node.operands[k]);
    if (copies != nullptr && k < last) {
      copy_values(values[k], node.operands[k].size, copies);
      values[k] = copies;
      copies += node.operands[k].size;
    }
  }
}

Place Evaluator::locate(const Node& node) {
  switch (node.kind) {
    case ExprKind::Variable:
      return {frame_ + node.variable_offset, node.size};
    case ExprKind::Member: {
      const Place base = locate(node.operands[0]);
      return {base.data + node.member_offset, node.size};
    }
    case ExprKind::Index: {
      const Place base = locate(node.operands[0]);
      const int index = element_index(node, evaluate(node.operands[1])[0]);
      if (!base.swizzled) return {base.data + index * node.element_size, node.size};
      Place component{base.data, 1, true};
      component.map[0] = base.map[index];
      return component;
    }
    case ExprKind::Swizzle: {
      const Place base = locate(node.operands[0]);
      Place place{base.data, node.size, true};
      for (int i = 0; i < node.size; ++i) {
        const int component = node.components[i];
        place.map[i] = base.swizzled ? base.map[component] : static_cast<std::int8_t>(component);
      }
      return place;
    }
    default:
      throw std::logic_error("glsl interpreter: an assignment to an expression that is not an lvalue");
  }
}

const double* Evaluator::operation(const Node& node) {
  double* out = frame_ + node.slot;
  switch (node.op) {
    case Operator::LogicalAnd:
      out[0] = truth(evaluate(node.operands[0])[0]) && truth(evaluate(node.operands[1])[0]) ? 1.0 : 0.0;
      return out;
    case Operator::LogicalOr:
      out[0] = truth(evaluate(node.operands[0])[0]) || truth(evaluate(node.operands[1])[0]) ? 1.0 : 0.0;
      return out;
    case Operator::PreIncrement:
    case Operator::PreDecrement:
    case Operator::PostIncrement:
    case Operator::PostDecrement:
      return increment(node);
    default:
      break;
  }
  if (node.float_scalars) {
    // Each value read before the next operand runs: nothing to protect.
    const double left = evaluate(node.operands[0])[0];
    out[0] = apply_float_scalars(node.op, left, evaluate(node.operands[1])[0]);
    return out;
  }
  if (node.operands.size() == 1) {
    apply_unary(node.op, node.operands[0].type, evaluate(node.operands[0]), out);
    return out;
  }
  const double* values[2];
  evaluate_operands(node, values);
  if (node.op == Operator::Equal || node.op == Operator::NotEqual) {
    const bool equal = values_equal(values[0], values[1], node.operands[0].size);
    out[0] = equal == (node.op == Operator::Equal) ? 1.0 : 0.0;
    return out;
  }
  apply_binary(node.op, node.operands[0].type, values[0], node.operands[1].type, values[1], node.type, out);
  return out;
}

const double* Evaluator::increment(const Node& node) {
  const Place target = locate(node.operands[0]);
  double gathered[4];
  const double* old = read(target, gathered);
  double updated[16];
  apply_increment(node.op == Operator::PreIncrement || node.op == Operator::PostIncrement, node.type, old, updated);
  double* out = frame_ + node.slot;
  // The prefix forms give the new value, the postfix ones the old (copied before it is overwritten).
  const bool prefix = node.op == Operator::PreIncrement || node.op == Operator::PreDecrement;
  copy_values(prefix ? updated : old, node.size, out);
  write(target, updated);
  return out;
}

const double* Evaluator::assign(const Node& node) {
  const Place target = locate(node.operands[0]);
  const double* value = evaluate(node.operands[1]);
  double* out = frame_ + node.slot;
  if (node.compound) {
    double gathered[4];
    const double* old = read(target, gathered);
    apply_binary(node.op, node.operands[0].type, old, node.operands[1].type, value, node.type, out);
    value = out;
  }
  write(target, value);
  if (!target.swizzled) return target.data;
  if (value != out) copy_values(value, node.size, out);
  return out;
}

const double* Evaluator::construct(const Node& node) {
  double* out = frame_ + node.slot;
  // Each operand's components go to the slot as soon as they are known: a later operand's side
  // effects cannot reach the slot, which is this node's alone.
  if (node.type.is_struct() || node.type.is_array()) {
    double* member = out;
    for (const Node& operand : node.operands) {
      copy_values(evaluate(operand), operand.size, member);
      member += operand.size;
    }
    return out;
  }
  if (node.operands.size() == 1) {
    construct_from_one(node.type, node.operands[0].type, evaluate(node.operands[0]), out);
    return out;
  }
  int filled = 0;
  for (const Node& operand : node.operands) {
    const double* value = evaluate(operand);
    for (int c = 0; c < operand.size && filled < node.size; ++c)
      out[filled++] = convert(value[c], operand.type.scalar, node.type.scalar);
  }
  return out;
}

const double* Evaluator::call(const Node& node) {
  const CompiledFunction& function = program_.functions[node.function];
  // The arguments in order into scratch (in and inout values, out ones zeroed), out and inout ones
  // located; only then into the parameters, which an argument calling this function would overwrite.
  double* arguments = frame_ + node.scratch;
  Place* place = places_ + node.first_place;
  double* argument = arguments;
  for (std::size_t k = 0; k < function.parameters.size(); ++k) {
    const Parameter& parameter = function.parameters[k];
    if (parameter.qualifier == ParameterQualifier::In) {
      copy_values(evaluate(node.operands[k]), parameter.size, argument);
    } else {
      *place = locate(node.operands[k]);
      if (parameter.qualifier == ParameterQualifier::InOut) {
        const double* value = read(*place, argument);
        if (value != argument) copy_values(value, parameter.size, argument);
      } else {
        std::fill_n(argument, parameter.size, 0.0);
      }
      ++place;
    }
    argument += parameter.size;
  }
  argument = arguments;
  for (const Parameter& parameter : function.parameters) {
    copy_values(argument, parameter.size, frame_ + parameter.offset);
    argument += parameter.size;
  }
  const Flow flow = execute(function.body);
  // The result first: copying out may write a variable the returned value points at.
  double* out = frame_ + node.slot;
  if (flow == Flow::Return && return_value_ != nullptr)
    copy_values(return_value_, node.size, out);
  else
    std::fill_n(out, node.size, 0.0);
  place = places_ + node.first_place;
  for (const Parameter& parameter : function.parameters)
    if (parameter.qualifier != ParameterQualifier::In) write(*place++, frame_ + parameter.offset);
  return out;
}

const double* Evaluator::builtin(const Node& node) {
  double* out = frame_ + node.slot;
  if (node.builtin == Builtin::Modf) {
    const double* x = evaluate(node.operands[0]);
    if (node.protects_operands) {
      copy_values(x, node.size, frame_ + node.scratch);
      x = frame_ + node.scratch;
    }
    const Place whole_place = locate(node.operands[1]);
    double whole[4];
    modf_parts(x, node.size, out, whole);
    write(whole_place, whole);
    return out;
  }
  const double* values[3];
  evaluate_operands(node, values);
  Argument arguments[3];
  for (std::size_t k = 0; k < node.operands.size(); ++k) arguments[k] = {values[k], &node.operands[k].type};
  apply_builtin(node.builtin, node.type, arguments, out);
  return out;
}

}  // namespace clmarch::glsl::interpreter

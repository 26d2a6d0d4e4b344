// Expressions of the packet translation (packet_emitter.hpp).
#include "glsl/packet_emitter.hpp"

#include "glsl/opencl_helpers.hpp"

#include <algorithm>
#include <utility>

namespace clmarch::glsl::packets {

PacketValue PacketEmitter::emit(const Expr& expr, Lines& pre) {
  switch (expr.kind) {
    case ExprKind::Constant: {
      if (!is_real(expr.type) && !is_uniform_scalar(expr.type)) unsupported(expr.location, "a constant of this type");
      PacketValue value;
      for (double component : expr.constant) {
        value.c.push_back(
            is_real(expr.type)
                ? literal(component)
                : scope_.scalar_literal(component, expr.type.scalar == Scalar::Uint ? Scalar::Uint : Scalar::Int));
      }
      return value;
    }
    case ExprKind::Variable:
      return variable(expr);
    case ExprKind::Swizzle: {
      const PacketValue base = emit(expr.operands[0], pre);
      if (!is_real(expr.type)) unsupported(expr.location, "a swizzle of an integer or bool vector");
      PacketValue value{{}, base.kind, base.stable};
      for (int i : expr.components) value.c.push_back(base.c.at(i));
      return value;
    }
    case ExprKind::Index: {
      const Expr& index = expr.operands[1];
      const Type& base_type = expr.operands[0].type;
      if (index.kind != ExprKind::Constant || !is_real(base_type)) {
        unsupported(expr.location, "an index computed at run time");
      }
      const PacketValue base = emit(expr.operands[0], pre);
      const int i = static_cast<int>(index.constant.at(0));
      const int size = base_type.is_matrix() ? base_type.rows : 1;
      PacketValue value{{}, base.kind, base.stable};
      for (int k = 0; k < size; ++k) value.c.push_back(base.c.at(i * size + k));
      return value;
    }
    case ExprKind::Member:
      unsupported(expr.location, "a struct");
    case ExprKind::Operation:
      return operation(expr, pre);
    case ExprKind::Assign:
      return assignment(expr, pre);
    case ExprKind::Select:
      return select(expr, pre);
    case ExprKind::Comma: {
      PacketValue last;
      for (const Expr& operand : expr.operands) last = emit(operand, pre);
      return last;
    }
    case ExprKind::Construct:
      return construct(expr, pre);
    case ExprKind::Call:
      return call(expr, pre);
    case ExprKind::BuiltinCall:
      return builtin(expr, pre);
  }
  unsupported(expr.location, "an expression of an unknown kind");
}

PacketValue PacketEmitter::variable(const Expr& expr) {
  const Variable& variable = module_.variables[expr.variable];
  PacketValue value;
  switch (variable.storage) {
    case Storage::Uniform:
      switch (variable.uniform) {
        case UniformKind::Time:
          value.c = {"iTime"};
          return value;
        case UniformKind::Frame:
          value.c = {fmt::format("convert_int_sat_rtz(floor(iTime * {}))", literal(kFramesPerSecond))};
          return value;
        case UniformKind::Resolution: {
          const UniformValues& uniforms = scope_.options().uniforms;
          value.c = {literal(uniforms.resolution_x), literal(uniforms.resolution_y), literal(1.0)};
          return value;
        }
        case UniformKind::Mouse:
          value.c.assign(4, literal(0.0));
          return value;
        case UniformKind::TimeDelta:
          value.c = {literal(1.0 / kFramesPerSecond)};
          return value;
        case UniformKind::None:
          break;
      }
      unsupported(expr.location, "a uniform of no kind");
    case Storage::GlobalConst:
      for (const Stmt& global : module_.globals) {
        if (global.variable == expr.variable && global.has_value && global.expression.kind == ExprKind::Constant) {
          Lines none;
          return emit(global.expression, none);
        }
      }
      break;
    case Storage::Global:
    case Storage::Local:
    case Storage::Parameter:
      break;
  }
  if (!is_real(variable.type) && !is_uniform_scalar(variable.type)) {
    unsupported(expr.location,
                fmt::format("'{}', of a type other than float, vectors, matrices, int, uint and bool", variable.name));
  }
  value.kind = is_real(variable.type) ? Kind::Packet : Kind::Uniform;
  value.stable = false;
  for (int i = 0; i < variable.type.components(); ++i) value.c.push_back(component_name(expr.variable, i));
  return value;
}

std::vector<PacketValue> PacketEmitter::in_order(const std::vector<Expr>& operands, Lines& pre) {
  std::vector<PacketValue> values;
  for (size_t i = 0; i < operands.size(); ++i) {
    values.push_back(emit(operands[i], pre));
    const bool later_effects = std::any_of(operands.begin() + static_cast<long>(i) + 1, operands.end(),
                                           [&](const Expr& e) { return has_effects(e); });
    if (later_effects) values.back() = stabilised(std::move(values.back()), operands[i].type, pre);
  }
  return values;
}

PacketValue PacketEmitter::operation(const Expr& expr, Lines& pre) {
  const Operator op = expr.op;
  if (is_increment(op)) return increment(expr, pre);
  if (op == Operator::LogicalAnd || op == Operator::LogicalOr || op == Operator::LogicalXor) return logical(expr, pre);
  if (expr.operands.size() == 1) {
    const PacketValue a = emit(expr.operands[0], pre);
    PacketValue value{{}, a.kind, true};
    for (const std::string& text : a.c) {
      switch (op) {
        case Operator::Negate:
          value.c.push_back(expr.type.scalar == Scalar::Int ? fmt::format("(int)(-(uint)({}))", text)
                                                            : fmt::format("-({})", text));
          break;
        case Operator::LogicalNot:
          value.c.push_back(a.kind == Kind::Mask ? fmt::format("~{}", text) : fmt::format("!({})", text));
          break;
        case Operator::BitwiseNot:
          value.c.push_back(fmt::format("~({})", text));
          break;
        default:
          unsupported(expr.location, "an operator of one operand other than -, ! and ~");
      }
    }
    return a.kind == Kind::Uniform ? PacketValue{value.c, Kind::Uniform, false} : bound(value, pre);
  }
  std::vector<PacketValue> operands = in_order(expr.operands, pre);
  switch (op) {
    case Operator::MatrixTimesVector:
    case Operator::VectorTimesMatrix:
    case Operator::MatrixTimesMatrix:
      return products(expr, operands[0], operands[1], pre);
    case Operator::Less:
    case Operator::Greater:
    case Operator::LessEqual:
    case Operator::GreaterEqual:
    case Operator::Equal:
    case Operator::NotEqual:
      return compare(expr, operands[0], operands[1], pre);
    default:
      return arithmetic(op, expr.type, operands[0], operands[1], pre);
  }
}

PacketValue PacketEmitter::arithmetic(Operator op, const Type& result, const PacketValue& a, const PacketValue& b,
                                      Lines& pre) {
  const size_t n = std::max(a.c.size(), b.c.size());
  const bool integer = result.scalar == Scalar::Int || result.scalar == Scalar::Uint;
  PacketValue value{{}, a.kind == Kind::Packet || b.kind == Kind::Packet ? Kind::Packet : Kind::Uniform, true};
  for (size_t i = 0; i < n; ++i) {
    const std::string& x = component(a, i);
    const std::string& y = component(b, i);
    if (integer && (op == Operator::Divide || op == Operator::Modulo)) {
      // GLSL leaves a division by zero undefined; the helper keeps it from trapping.
      value.c.push_back(fmt::format("{}({}, {})", opencl::integer_divide_helper(scope_, op, result, result), x, y));
      continue;
    }
    if (op == Operator::ShiftLeft || op == Operator::ShiftRight) {
      // GLSL leaves shifts past the width undefined; C's are undefined behaviour.
      value.c.push_back(fmt::format("{} {} ({} & 31)", x, opencl::c_symbol(op), y));
      continue;
    }
    const char* symbol = opencl::c_symbol(op);
    // GLSL's ints wrap around; C's signed overflow is undefined, so it goes through uint.
    const bool wraps =
        result.scalar == Scalar::Int && (op == Operator::Add || op == Operator::Subtract || op == Operator::Multiply);
    value.c.push_back(wraps ? fmt::format("(int)((uint){} {} (uint){})", x, symbol, y)
                            : fmt::format("{} {} {}", x, symbol, y));
  }
  if (value.kind == Kind::Uniform) {
    value.stable = false;
    for (std::string& text : value.c) text = "(" + text + ")";
    return value;
  }
  return bound(value, pre);
}

PacketValue PacketEmitter::compare(const Expr& expr, const PacketValue& a, const PacketValue& b, Lines& pre) {
  const char* symbol = opencl::c_symbol(expr.op);
  // == and != compare whole values: every component equal, or some component different.
  const bool any = expr.op == Operator::NotEqual;
  std::vector<std::string> tests;
  for (size_t i = 0; i < a.c.size(); ++i) tests.push_back(fmt::format("{} {} {}", a.c[i], symbol, b.c[i]));
  if (a.kind == Kind::Uniform && b.kind == Kind::Uniform) {
    return PacketValue{{fmt::format("({})", fmt::join(tests, any ? " || " : " && "))}, Kind::Uniform, false};
  }
  if (a.kind == Kind::Mask || b.kind == Kind::Mask) unsupported(expr.location, "bools of the point compared");
  return bound(PacketValue{{fmt::format("{}", fmt::join(tests, any ? " | " : " & "))}, Kind::Mask, true}, pre);
}

PacketValue PacketEmitter::logical(const Expr& expr, Lines& pre) {
  const PacketValue a = emit(expr.operands[0], pre);
  Lines right;
  const PacketValue b = emit(expr.operands[1], right);
  // The right side runs whatever the left one is (on every lane, or before C's && tests the
  // left), which only a right side without effects allows.
  if (!right.empty() || (a.kind != Kind::Uniform || b.kind != Kind::Uniform)) {
    if (has_effects(expr.operands[1])) {
      unsupported(expr.location, "&&, || or ^^ with side effects on its right, after a bool of the point or a call");
    }
    pre.insert(pre.end(), right.begin(), right.end());
  }
  if (a.kind == Kind::Uniform && b.kind == Kind::Uniform) {
    const char* symbol = expr.op == Operator::LogicalAnd ? "&&" : expr.op == Operator::LogicalOr ? "||" : "!=";
    return PacketValue{{fmt::format("(!!({}) {} !!({}))", a.c[0], symbol, b.c[0])}, Kind::Uniform, false};
  }
  auto mask = [](const PacketValue& v) {
    return v.kind == Kind::Mask ? v.c[0] : fmt::format("(vint)(-(int)!!({}))", v.c[0]);
  };
  const char* symbol = expr.op == Operator::LogicalAnd ? "&" : expr.op == Operator::LogicalOr ? "|" : "^";
  return bound(PacketValue{{fmt::format("{} {} {}", mask(a), symbol, mask(b))}, Kind::Mask, true}, pre);
}

PacketValue PacketEmitter::select(const Expr& expr, Lines& pre) {
  const PacketValue condition = emit(expr.operands[0], pre);
  if (has_effects(expr.operands[1]) || has_effects(expr.operands[2])) {
    unsupported(expr.location, "a ?: with side effects in a branch");
  }
  if (!is_real(expr.type) && condition.kind == Kind::Mask) {
    unsupported(expr.location, "a ?: of the point choosing ints or bools");
  }
  const PacketValue a = emit(expr.operands[1], pre);
  const PacketValue b = emit(expr.operands[2], pre);
  if (a.kind == Kind::Mask || b.kind == Kind::Mask) unsupported(expr.location, "a ?: choosing bools of the point");
  if (condition.kind == Kind::Uniform && a.kind == Kind::Uniform && b.kind == Kind::Uniform) {
    PacketValue value{{}, Kind::Uniform, false};
    for (size_t i = 0; i < a.c.size(); ++i)
      value.c.push_back(fmt::format("(({}) ? ({}) : ({}))", condition.c[0], a.c[i], b.c[i]));
    return value;
  }
  PacketValue value{{}, Kind::Packet, true};
  for (size_t i = 0; i < a.c.size(); ++i) {
    value.c.push_back(condition.kind == Kind::Mask
                          ? fmt::format("select({}, {}, {})", packet(b, i), packet(a, i), condition.c[0])
                          : fmt::format("({}) ? {} : {}", condition.c[0], packet(a, i), packet(b, i)));
  }
  return bound(value, pre);
}

std::vector<std::string> PacketEmitter::places(const Expr& expr) {
  switch (expr.kind) {
    case ExprKind::Variable: {
      const Variable& variable = module_.variables[expr.variable];
      std::vector<std::string> names;
      for (int i = 0; i < variable.type.components(); ++i) names.push_back(component_name(expr.variable, i));
      return names;
    }
    case ExprKind::Swizzle: {
      const std::vector<std::string> base = places(expr.operands[0]);
      std::vector<std::string> names;
      for (int i : expr.components) names.push_back(base.at(i));
      return names;
    }
    case ExprKind::Index: {
      const Expr& index = expr.operands[1];
      if (index.kind != ExprKind::Constant) unsupported(expr.location, "a write at an index computed at run time");
      const std::vector<std::string> base = places(expr.operands[0]);
      const Type& base_type = expr.operands[0].type;
      const int size = base_type.is_matrix() ? base_type.rows : 1;
      const int i = static_cast<int>(index.constant.at(0));
      return std::vector<std::string>(base.begin() + i * size, base.begin() + (i + 1) * size);
    }
    default:
      unsupported(expr.location, "a write to this kind of place");
  }
}

void PacketEmitter::store(const std::vector<std::string>& targets, const Type& type, PacketValue value, Lines& pre) {
  // q.xy = q.yx reads both before it writes either.
  if (targets.size() > 1) value = stabilised(std::move(value), type, pre);
  for (size_t i = 0; i < targets.size(); ++i) {
    pre.push_back(fmt::format("{} = {};", targets[i], is_real(type) ? packet(value, i) : component(value, i)));
  }
}

PacketValue PacketEmitter::assignment(const Expr& expr, Lines& pre) {
  const Expr& target = expr.operands[0];
  const std::vector<std::string> targets = places(target);
  PacketValue value = emit(expr.operands[1], pre);
  if (expr.compound) {
    PacketValue current{targets, is_real(target.type) ? Kind::Packet : Kind::Uniform, false};
    if (expr.op == Operator::MatrixTimesMatrix || expr.op == Operator::VectorTimesMatrix) {
      value = products(expr, current, value, pre);
    } else {
      value = arithmetic(expr.op, target.type, current, value, pre);
    }
  }
  if (value.kind == Kind::Mask) unsupported(expr.location, "a bool of the point stored");
  value = stabilised(std::move(value), target.type, pre);
  store(targets, target.type, value, pre);
  return value;
}

PacketValue PacketEmitter::increment(const Expr& expr, Lines& pre) {
  const Expr& target = expr.operands[0];
  const std::vector<std::string> targets = places(target);
  const bool real = is_real(target.type);
  PacketValue before = stabilised(PacketValue{targets, real ? Kind::Packet : Kind::Uniform, false}, target.type, pre);
  PacketValue one{{real ? literal(1.0) : "1"}, Kind::Uniform, true};
  const bool up = expr.op == Operator::PreIncrement || expr.op == Operator::PostIncrement;
  PacketValue after =
      stabilised(arithmetic(up ? Operator::Add : Operator::Subtract, target.type, before, one, pre), target.type, pre);
  store(targets, target.type, after, pre);
  return expr.op == Operator::PreIncrement || expr.op == Operator::PreDecrement ? after : before;
}

PacketValue PacketEmitter::products(const Expr& expr, const PacketValue& a, const PacketValue& b, Lines& pre) {
  const Type& at = expr.operands[0].type;
  const Type& bt = expr.operands[1].type;
  auto sum = [](const std::vector<std::string>& terms) { return fmt::format("{}", fmt::join(terms, " + ")); };
  PacketValue value{{}, a.kind == Kind::Packet || b.kind == Kind::Packet ? Kind::Packet : Kind::Uniform, true};
  switch (expr.op) {
    case Operator::MatrixTimesVector:
      // (m v)_i = sum_j m[j][i] v_j
      for (int i = 0; i < at.rows; ++i) {
        std::vector<std::string> terms;
        for (int j = 0; j < at.columns; ++j) terms.push_back(fmt::format("{} * {}", a.c[j * at.rows + i], b.c[j]));
        value.c.push_back(sum(terms));
      }
      break;
    case Operator::VectorTimesMatrix:
      // (v m)_j = sum_i v_i m[j][i] = (transpose(m) v)_j
      for (int j = 0; j < bt.columns; ++j) {
        std::vector<std::string> terms;
        for (int i = 0; i < bt.rows; ++i) terms.push_back(fmt::format("{} * {}", a.c[i], b.c[j * bt.rows + i]));
        value.c.push_back(sum(terms));
      }
      break;
    default:
      // (a b)[j][i] = sum_l a[l][i] b[j][l]
      for (int j = 0; j < bt.columns; ++j) {
        for (int i = 0; i < at.rows; ++i) {
          std::vector<std::string> terms;
          for (int l = 0; l < at.columns; ++l) {
            terms.push_back(fmt::format("{} * {}", a.c[l * at.rows + i], b.c[j * bt.rows + l]));
          }
          value.c.push_back(sum(terms));
        }
      }
      break;
  }
  if (value.kind == Kind::Uniform) {
    for (std::string& text : value.c) text = "(" + text + ")";
    value.stable = false;
    return value;
  }
  return bound(value, pre);
}

PacketValue PacketEmitter::construct(const Expr& expr, Lines& pre) {
  const Type& type = expr.type;
  std::vector<PacketValue> operands = in_order(expr.operands, pre);
  for (const PacketValue& operand : operands) {
    if (operand.kind == Kind::Mask) unsupported(expr.location, "a constructor of bools of the point");
  }
  if (is_uniform_scalar(type)) {
    const PacketValue& from = operands.at(0);
    const Type& from_type = expr.operands[0].type;
    if (from.kind == Kind::Packet) unsupported(expr.location, "an int or bool computed from the point");
    const std::string& text = from.c.at(0);
    PacketValue value{{}, Kind::Uniform, false};
    if (type.scalar == Scalar::Bool) {
      value.c.push_back(fmt::format("(({}) != 0)", text));
    } else if (from_type.scalar == Scalar::Float) {
      value.c.push_back(fmt::format("convert_{}_sat_rtz({})", c_scalar(type.scalar), text));
    } else {
      value.c.push_back(fmt::format("({})({})", c_scalar(type.scalar), text));
    }
    return value;
  }
  if (!is_real(type)) unsupported(expr.location, "a constructor of this type");
  // Components in order; in a packet result, uniform ones are broadcast to vfloat.
  const bool packet_result = std::any_of(operands.begin(), operands.end(),
                                         [](const PacketValue& operand) { return operand.kind == Kind::Packet; });
  auto as_result = [&](const std::string& text) { return packet_result ? fmt::format("(vfloat)({})", text) : text; };
  std::vector<std::string> flat;
  bool stable = true;
  for (size_t k = 0; k < operands.size(); ++k) {
    const bool converted = expr.operands[k].type.scalar != Scalar::Float;
    for (const std::string& text : operands[k].c) {
      const std::string real = converted ? fmt::format("(real)({})", text) : text;
      flat.push_back(operands[k].kind == Kind::Packet ? real : as_result(real));
    }
    stable = stable && operands[k].stable;
  }
  PacketValue value{{}, packet_result ? Kind::Packet : Kind::Uniform, stable};
  const int n = type.components();
  const std::string zero = as_result(literal(0.0)), one = as_result(literal(1.0));
  if (type.is_matrix() && operands.size() == 1 && flat.size() == 1) {
    for (int j = 0; j < type.columns; ++j) {
      for (int i = 0; i < type.rows; ++i) value.c.push_back(i == j ? flat[0] : zero);
    }
  } else if (type.is_matrix() && operands.size() == 1 && expr.operands[0].type.is_matrix()) {
    const Type& from = expr.operands[0].type;
    for (int j = 0; j < type.columns; ++j) {
      for (int i = 0; i < type.rows; ++i) {
        value.c.push_back(j < from.columns && i < from.rows ? flat[j * from.rows + i] : i == j ? one : zero);
      }
    }
  } else if (flat.size() == 1) {
    value.c.assign(n, flat[0]);
  } else {
    value.c.assign(flat.begin(), flat.begin() + n);
  }
  return value;
}

PacketValue PacketEmitter::call(const Expr& expr, Lines& pre) {
  const Function& callee = module_.functions[expr.function];
  std::vector<std::string> arguments{"iTime"};
  if (!info_.globals_type.empty()) arguments.emplace_back("globals");
  std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> write_backs;
  std::vector<PacketValue> inputs;
  for (size_t k = 0; k < expr.operands.size(); ++k) {
    const Expr& argument = expr.operands[k];
    const Variable& parameter = module_.variables[callee.parameters[k]];
    const bool real = is_real(parameter.type);
    const std::string type = real ? "vfloat" : c_scalar(parameter.type.scalar);
    if (parameter.qualifier == ParameterQualifier::In) {
      PacketValue value = emit(argument, pre);
      if (value.kind == Kind::Mask) unsupported(argument.location, "a bool of the point passed to a function");
      const bool later_effects = std::any_of(expr.operands.begin() + static_cast<long>(k) + 1, expr.operands.end(),
                                             [&](const Expr& e) { return has_effects(e); });
      if (later_effects) value = stabilised(std::move(value), argument.type, pre);
      for (size_t i = 0; i < value.c.size(); ++i) arguments.push_back(real ? packet(value, i) : value.c[i]);
      continue;
    }
    // out and inout through temporaries, copied back after the call in the arguments' order.
    const std::vector<std::string> targets = places(argument);
    std::vector<std::string> temporaries;
    for (const std::string& target : targets) {
      const std::string name = fmt::format("tmp{}", temporaries_++);
      const std::string initial = parameter.qualifier == ParameterQualifier::InOut ? target
                                  : real                                           ? literal(0.0)
                                                                                   : std::string("0");
      pre.push_back(fmt::format("{} {} = {};", type, name, initial));
      arguments.push_back("&" + name);
      temporaries.push_back(name);
    }
    write_backs.emplace_back(targets, temporaries);
  }
  const std::string text = fmt::format("{}({})", info_.names[expr.function], fmt::join(arguments, ", "));
  const Type& result = callee.return_type;
  PacketValue value{{}, Kind::Packet, true};
  if (result.is_void()) {
    pre.push_back(text + ";");
  } else if (!is_real(result)) {
    value = PacketValue{{temporary(c_scalar(result.scalar), text, pre)}, Kind::Uniform, true};
  } else if (result.components() == 1) {
    value.c.push_back(temporary("vfloat", text, pre));
  } else {
    const std::string name = temporary(info_.return_types[expr.function], text, pre);
    for (int i = 0; i < result.components(); ++i) value.c.push_back(fmt::format("{}.c[{}]", name, i));
  }
  for (const auto& [targets, temporaries] : write_backs) {
    for (size_t i = 0; i < targets.size(); ++i) pre.push_back(fmt::format("{} = {};", targets[i], temporaries[i]));
  }
  return value;
}

}  // namespace clmarch::glsl::packets

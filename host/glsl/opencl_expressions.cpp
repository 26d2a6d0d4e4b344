// Expressions of the OpenCL translation (opencl_emitter.hpp): operators, variables, swizzles,
// indexing, assignments, constructors and calls of user functions.
#include "glsl/opencl_emitter.hpp"
#include "glsl/opencl_helpers.hpp"

#include <fmt/format.h>

#include <functional>
#include <stdexcept>

namespace clmarch::glsl::opencl {

FunctionEmitter::FunctionEmitter(Scope& scope, const ProgramInfo& info, std::string globals)
    : scope_(scope),
      info_(info),
      globals_(std::move(globals)),
      local_names_(scope.module().variables.size()),
      out_parameter_(scope.module().variables.size(), false) {}

bool FunctionEmitter::has_effects(const Expr& expr) const {
  switch (expr.kind) {
    case ExprKind::Assign:
      return true;
    case ExprKind::Operation:
      if (expr.op == Operator::PreIncrement || expr.op == Operator::PreDecrement ||
          expr.op == Operator::PostIncrement || expr.op == Operator::PostDecrement) {
        return true;
      }
      break;
    case ExprKind::Call: {
      if (info_.writes_globals[expr.function]) return true;
      for (int parameter : scope_.module().functions[expr.function].parameters) {
        if (scope_.module().variables[parameter].qualifier != ParameterQualifier::In) return true;
      }
      break;
    }
    case ExprKind::BuiltinCall:
      if (expr.builtin == Builtin::Modf) return true;
      break;
    default:
      break;
  }
  for (const Expr& operand : expr.operands) {
    if (has_effects(operand)) return true;
  }
  return false;
}

std::string FunctionEmitter::temporary_name() { return fmt::format("tmp{}", ++temporaries_); }

Value FunctionEmitter::temporary(const Value& value, const Type& type, Lines& pre) {
  const std::string name = temporary_name();
  pre.push_back(fmt::format("{} {} = {};", scope_.type(type), name, value.text));
  return Value{name, kPostfix, true};
}

namespace {

// Hoists, into temporaries after their own hoisted statements, the operands that a later operand's
// side effects (or hoisted statements) could change or that run before them, so that the
// operands' evaluations happen in GLSL's left-to-right order whatever order C picks.
void order_operands(std::vector<Lines>& hoisted, std::vector<Value>& values, const std::vector<bool>& effects,
                    const std::vector<Type>& types, Lines& pre,
                    const std::function<Value(const Value&, const Type&, Lines&)>& temporary) {
  int last = -1;
  for (size_t i = 0; i < values.size(); ++i) {
    if (!hoisted[i].empty() || effects[i]) last = static_cast<int>(i);
  }
  for (size_t i = 0; i < values.size(); ++i) {
    pre.insert(pre.end(), hoisted[i].begin(), hoisted[i].end());
    bool later_reads = false;
    for (size_t j = i + 1; j < values.size(); ++j) later_reads = later_reads || !values[j].stable;
    const int at = static_cast<int>(i);
    if (!values[i].stable && (at < last || (at == last && effects[i] && later_reads))) {
      values[i] = temporary(values[i], types[i], pre);
    }
  }
}

}  // namespace

std::vector<Value> FunctionEmitter::in_order(const std::vector<const Expr*>& operands, Lines& pre) {
  std::vector<Lines> hoisted(operands.size());
  std::vector<Value> values;
  std::vector<bool> effects;
  std::vector<Type> types;
  for (size_t i = 0; i < operands.size(); ++i) {
    values.push_back(emit(*operands[i], hoisted[i]));
    effects.push_back(has_effects(*operands[i]));
    types.push_back(operands[i]->type);
  }
  order_operands(hoisted, values, effects, types, pre,
                 [this](const Value& v, const Type& t, Lines& lines) { return temporary(v, t, lines); });
  return values;
}

Value FunctionEmitter::emit(const Expr& expr, Lines& pre) {
  switch (expr.kind) {
    case ExprKind::Constant: {
      Value value;
      value.text = scope_.constant(expr.type, expr.constant.data(), &value.precedence);
      value.stable = true;
      return value;
    }
    case ExprKind::Variable:
      return variable(expr);
    case ExprKind::Swizzle:
      return swizzle(expr, pre);
    case ExprKind::Index:
      return index(expr, pre);
    case ExprKind::Member: {
      const Value base = emit(expr.operands[0], pre);
      return Value{parenthesised(base.text, base.precedence, kPostfix) + "." +
                   scope_.member_name(expr.operands[0].type, expr.member)};
    }
    case ExprKind::Operation:
      return operation(expr, pre);
    case ExprKind::Assign:
      return assignment(expr, pre, false);
    case ExprKind::Select:
      return select(expr, pre);
    case ExprKind::Comma:
      for (size_t i = 0; i + 1 < expr.operands.size(); ++i) effect_statements(expr.operands[i], pre);
      return emit(expr.operands.back(), pre);
    case ExprKind::Construct:
      return construct(expr, pre);
    case ExprKind::Call:
      return call(expr, pre);
    case ExprKind::BuiltinCall:
      return builtin(expr, pre);
  }
  throw std::logic_error("opencl translation: unknown expression kind");
}

Value FunctionEmitter::variable(const Expr& expr) {
  const Variable& variable = scope_.module().variables[expr.variable];
  switch (variable.storage) {
    case Storage::Uniform: {
      const UniformValues& uniforms = scope_.options().uniforms;
      const std::string r = scope_.real();
      auto literal = [this](double v) { return scope_.scalar_literal(v, Scalar::Float); };
      switch (variable.uniform) {
        case UniformKind::Time:
          return Value{globals_ + "->iTime", kPostfix, true};
        case UniformKind::Frame:
          return Value{globals_ + "->iFrame", kPostfix, true};
        case UniformKind::Resolution:
          return Value{fmt::format("({}3)({}, {}, {})", r, literal(uniforms.resolution_x),
                                   literal(uniforms.resolution_y), literal(1.0)),
                       kUnary, true};
        case UniformKind::Mouse:
          return Value{fmt::format("({}4)({})", r, literal(0.0)), kUnary, true};
        case UniformKind::TimeDelta:
          return Value{literal(1.0 / kFramesPerSecond), kPostfix, true};
        case UniformKind::None:
          break;
      }
      throw std::logic_error("opencl translation: a uniform of no kind");
    }
    case Storage::Global:
    case Storage::GlobalConst:
      return Value{fmt::format("{}->{}_", globals_, variable.name)};
    case Storage::Local:
    case Storage::Parameter:
      break;
  }
  const std::string name = local_name(expr.variable);
  return Value{out_parameter_[expr.variable] ? std::string("(*") + name + ")" : name};
}

namespace {

std::string letters(const std::vector<int>& components) {
  std::string text;
  for (int c : components) text += component_letter(c);
  return text;
}

// A swizzle of a swizzle reads the inner one's components.
std::vector<int> composed(const std::vector<int>& inner, const std::vector<int>& outer) {
  std::vector<int> components;
  for (int c : outer) components.push_back(inner[c]);
  return components;
}

}  // namespace

Value FunctionEmitter::swizzle(const Expr& expr, Lines& pre) {
  const Expr* base = &expr.operands[0];
  std::vector<int> components = expr.components;
  while (base->kind == ExprKind::Swizzle) {
    components = composed(base->components, components);
    base = &base->operands[0];
  }
  const Value value = emit(*base, pre);
  if (base->type.is_scalar()) {
    if (components.size() == 1) return value;
    return Value{fmt::format("({})({})", scope_.type(expr.type), value.text), kUnary, value.stable};
  }
  return Value{parenthesised(value.text, value.precedence, kPostfix) + "." + letters(components), kPostfix,
               value.stable};
}

Value FunctionEmitter::index(const Expr& expr, Lines& pre) {
  const Type& base_type = expr.operands[0].type;
  const Expr& index_expr = expr.operands[1];
  if (index_expr.kind == ExprKind::Constant) {
    const Value base = emit(expr.operands[0], pre);
    const std::string text = parenthesised(base.text, base.precedence, kPostfix);
    const int i = static_cast<int>(index_expr.constant[0]);
    if (base_type.is_array()) return Value{fmt::format("{}.e[{}]", text, i), kPostfix, base.stable};
    if (base_type.is_matrix()) return Value{fmt::format("{}.c[{}]", text, i), kPostfix, base.stable};
    return Value{fmt::format("{}.{}", text, component_letter(i)), kPostfix, base.stable};
  }
  const std::vector<Value> values = in_order({&expr.operands[0], &index_expr}, pre);
  const std::string text = parenthesised(values[0].text, values[0].precedence, kPostfix);
  if (is_single_vector(base_type)) {
    return Value{fmt::format("{}({}, {})", vector_at_helper(scope_, base_type), values[0].text, values[1].text)};
  }
  // GLSL leaves an index out of range undefined; clamped, it reads and writes inside the value.
  const int count = base_type.is_array() ? base_type.array_size : base_type.columns;
  return Value{
      fmt::format("{}.{}[min(max({}, 0), {})]", text, base_type.is_array() ? "e" : "c", values[1].text, count - 1)};
}

Value FunctionEmitter::operation(const Expr& expr, Lines& pre) {
  const Type& type = expr.type;
  switch (expr.op) {
    case Operator::Negate: {
      const Value a = emit(expr.operands[0], pre);
      if (type.is_matrix()) return Value{fmt::format("{}({})", matrix_negate_helper(scope_, type), a.text)};
      if (type.scalar == Scalar::Int) {
        // Negating INT_MIN overflows: negate the bits as uint.
        const std::string n = type.rows == 1 ? "" : std::to_string(type.rows);
        return Value{fmt::format("as_int{}(-as_uint{}({}))", n, n, a.text)};
      }
      return Value{negated(a.text, a.precedence), kUnary, a.stable};
    }
    case Operator::LogicalNot: {
      const Value a = emit(expr.operands[0], pre);
      return Value{std::string("!") + parenthesised(a.text, a.precedence, kUnary), kUnary, a.stable};
    }
    case Operator::BitwiseNot: {
      const Value a = emit(expr.operands[0], pre);
      return Value{std::string("~") + parenthesised(a.text, a.precedence, kUnary), kUnary, a.stable};
    }
    case Operator::PreIncrement:
    case Operator::PreDecrement:
    case Operator::PostIncrement:
    case Operator::PostDecrement:
      return increment(expr, pre, false);
    case Operator::LogicalAnd:
    case Operator::LogicalOr:
      return logical(expr, pre);
    default:
      break;
  }
  const std::vector<Value> v = in_order({&expr.operands[0], &expr.operands[1]}, pre);
  const Type& a_type = expr.operands[0].type;
  const bool stable = v[0].stable && v[1].stable;
  switch (expr.op) {
    case Operator::Less:
    case Operator::Greater:
    case Operator::LessEqual:
    case Operator::GreaterEqual: {
      const char* symbol = expr.op == Operator::Less        ? "<"
                           : expr.op == Operator::Greater   ? ">"
                           : expr.op == Operator::LessEqual ? "<="
                                                            : ">=";
      return Value{fmt::format("{} {} {}", parenthesised(v[0].text, v[0].precedence, kShift), symbol,
                               parenthesised(v[1].text, v[1].precedence, kShift)),
                   kRelational, stable};
    }
    case Operator::Equal:
    case Operator::NotEqual: {
      const bool equal = expr.op == Operator::Equal;
      const std::string a = parenthesised(v[0].text, v[0].precedence, kRelational);
      const std::string b = parenthesised(v[1].text, v[1].precedence, kRelational);
      if (is_single_scalar(a_type)) return Value{fmt::format("{} {} {}", a, equal ? "==" : "!=", b), kEquality, stable};
      if (is_single_vector(a_type))
        return Value{fmt::format("{}({} {} {})", equal ? "all" : "any", a, equal ? "==" : "!=", b)};
      const std::string test = equal_expression(scope_, a_type, v[0].text, v[1].text);
      return equal ? Value{test} : Value{std::string("!") + test, kUnary};
    }
    case Operator::LogicalXor:
      // bools are 0 or 1, so != is ^^.
      return Value{fmt::format("{} != {}", parenthesised(v[0].text, v[0].precedence, kRelational),
                               parenthesised(v[1].text, v[1].precedence, kRelational)),
                   kEquality, stable};
    default:
      break;
  }
  Value result = arithmetic(expr.op, type, v[0], a_type, v[1], expr.operands[1].type);
  result.stable = stable;
  return result;
}

Value FunctionEmitter::arithmetic(Operator op, const Type& result, const Value& a, const Type& a_type, const Value& b,
                                  const Type& b_type) {
  switch (op) {
    case Operator::MatrixTimesVector:
      return Value{fmt::format("{}({}, {})", matrix_times_vector_helper(scope_, a_type), a.text, b.text)};
    case Operator::VectorTimesMatrix:
      return Value{fmt::format("{}({}, {})", vector_times_matrix_helper(scope_, b_type), a.text, b.text)};
    case Operator::MatrixTimesMatrix:
      return Value{fmt::format("{}({}, {})", matrix_times_matrix_helper(scope_, a_type, b_type), a.text, b.text)};
    default:
      break;
  }
  if (a_type.is_matrix() || b_type.is_matrix()) {
    return Value{fmt::format("{}({}, {})", matrix_componentwise_helper(scope_, op, a_type, b_type), a.text, b.text)};
  }
  const bool integer = result.scalar == Scalar::Int || result.scalar == Scalar::Uint;
  if (integer && (op == Operator::Divide || op == Operator::Modulo)) {
    return Value{fmt::format("{}({}, {})", integer_divide_helper(scope_, op, a_type, b_type), a.text, b.text)};
  }
  const char* symbol = "";
  int precedence = kAdditive;
  switch (op) {
    case Operator::Add:
      symbol = "+";
      break;
    case Operator::Subtract:
      symbol = "-";
      break;
    case Operator::Multiply:
      symbol = "*", precedence = kMultiplicative;
      break;
    case Operator::Divide:
      symbol = "/", precedence = kMultiplicative;
      break;
    case Operator::ShiftLeft:
      symbol = "<<", precedence = kShift;
      break;
    case Operator::ShiftRight:
      symbol = ">>", precedence = kShift;
      break;
    case Operator::BitwiseAnd:
      symbol = "&", precedence = kBitAnd;
      break;
    case Operator::BitwiseOr:
      symbol = "|", precedence = kBitOr;
      break;
    case Operator::BitwiseXor:
      symbol = "^", precedence = kBitXor;
      break;
    default:
      throw std::logic_error("opencl translation: not an arithmetic operator");
  }
  std::string b_text = b.text;
  int b_precedence = b.precedence;
  if ((op == Operator::ShiftLeft || op == Operator::ShiftRight) && b_type.scalar != a_type.scalar) {
    // GLSL shifts an int by a uint and the reverse; OpenCL wants one element type.
    const std::string n = b_type.rows == 1 ? "" : std::to_string(b_type.rows);
    b_text = fmt::format("as_{}{}({})", a_type.scalar == Scalar::Int ? "int" : "uint", n, b.text);
    b_precedence = kPostfix;
  }
  const bool wraps = result.scalar == Scalar::Int && (op == Operator::Add || op == Operator::Subtract ||
                                                      op == Operator::Multiply || op == Operator::ShiftLeft);
  if (!wraps) {
    // Left-associative: the right operand needs parentheses at its own level too.
    return Value{fmt::format("{} {} {}", parenthesised(a.text, a.precedence, precedence), symbol,
                             parenthesised(b_text, b_precedence, precedence + 1)),
                 precedence};
  }
  // Signed overflow is undefined in OpenCL C: the bits are computed as uint, which wraps.
  auto as_uint = [](const Value& v, const Type& t) {
    if (v.stable && t.is_scalar() && v.text.find_first_not_of("0123456789") == std::string::npos) return v.text + "u";
    return fmt::format("as_uint{}({})", t.rows == 1 ? "" : std::to_string(t.rows), v.text);
  };
  const std::string right =
      op == Operator::ShiftLeft ? parenthesised(b_text, b_precedence, precedence + 1) : as_uint(b, b_type);
  return Value{fmt::format("as_int{}({} {} {})", result.rows == 1 ? "" : std::to_string(result.rows),
                           as_uint(a, a_type), symbol, right)};
}

Value FunctionEmitter::logical(const Expr& expr, Lines& pre) {
  const bool is_and = expr.op == Operator::LogicalAnd;
  const int precedence = is_and ? kLogicalAnd : kLogicalOr;
  const Value a = emit(expr.operands[0], pre);
  Lines right_pre;
  const Value b = emit(expr.operands[1], right_pre);
  if (right_pre.empty()) {
    return Value{fmt::format("{} {} {}", parenthesised(a.text, a.precedence, precedence), is_and ? "&&" : "||",
                             parenthesised(b.text, b.precedence, precedence + 1)),
                 precedence, a.stable && b.stable};
  }
  // The right operand needs statements: they run only where C's && or || would evaluate it.
  const std::string name = temporary_name();
  pre.push_back(fmt::format("bool {} = {};", name, a.text));
  pre.push_back(fmt::format("if ({}{}) {{", is_and ? "" : "!", name));
  for (const std::string& line : right_pre) pre.push_back(std::string("  ") + line);
  pre.push_back(fmt::format("  {} = {};", name, b.text));
  pre.push_back("}");
  return Value{name, kPostfix, true};
}

Value FunctionEmitter::select(const Expr& expr, Lines& pre) {
  const Value condition = emit(expr.operands[0], pre);
  Lines then_pre;
  Lines else_pre;
  const bool is_void = expr.type.is_void();
  if (is_void) {
    effect_statements(expr.operands[1], then_pre);
    effect_statements(expr.operands[2], else_pre);
  }
  const Value a = is_void ? Value{} : emit(expr.operands[1], then_pre);
  const Value b = is_void ? Value{} : emit(expr.operands[2], else_pre);
  if (!is_void && then_pre.empty() && else_pre.empty()) {
    return Value{fmt::format("{} ? {} : {}", parenthesised(condition.text, condition.precedence, kLogicalOr),
                             parenthesised(a.text, a.precedence, kAssignment),
                             parenthesised(b.text, b.precedence, kConditional)),
                 kConditional, condition.stable && a.stable && b.stable};
  }
  // Only the chosen branch runs, with the statements it needs.
  std::string name;
  if (!is_void) {
    name = temporary_name();
    pre.push_back(fmt::format("{} {};", scope_.type(expr.type), name));
    then_pre.push_back(fmt::format("{} = {};", name, a.text));
    else_pre.push_back(fmt::format("{} = {};", name, b.text));
  }
  pre.push_back(fmt::format("if ({}) {{", condition.text));
  for (const std::string& line : then_pre) pre.push_back(std::string("  ") + line);
  pre.push_back("} else {");
  for (const std::string& line : else_pre) pre.push_back(std::string("  ") + line);
  pre.push_back("}");
  return Value{name, kPostfix, true};
}

std::string FunctionEmitter::index_text(const Expr& index, Lines& pre) {
  if (index.kind == ExprKind::Constant) return std::to_string(static_cast<int>(index.constant[0]));
  const Value value = emit(index, pre);
  // A local variable stays as it is, for readability; anything else is read once, here.
  const bool plain = index.kind == ExprKind::Variable &&
                     scope_.module().variables[index.variable].storage != Storage::Global &&
                     scope_.module().variables[index.variable].storage != Storage::GlobalConst;
  return plain ? value.text : temporary(value, index.type, pre).text;
}

LValue FunctionEmitter::lvalue(const Expr& expr, Lines& pre) {
  LValue place;
  place.type = expr.type;
  switch (expr.kind) {
    case ExprKind::Variable: {
      const Variable& variable = scope_.module().variables[expr.variable];
      place.text = this->variable(expr).text;
      place.variable = expr.variable;
      if (variable.storage == Storage::Local || variable.storage == Storage::Parameter) {
        place.plain_variable = true;
        const std::string name = local_name(expr.variable);
        place.address = out_parameter_[expr.variable] ? name : std::string("&") + name;
      }
      return place;
    }
    case ExprKind::Member: {
      const LValue base = lvalue(expr.operands[0], pre);
      place.text = base.text + "." + scope_.member_name(expr.operands[0].type, expr.member);
      place.variable = base.variable;
      return place;
    }
    case ExprKind::Swizzle: {
      const LValue base = lvalue(expr.operands[0], pre);
      if (expr.operands[0].type.is_scalar()) return base;
      place.variable = base.variable;
      place.swizzle = base.swizzle.empty() ? expr.components : composed(base.swizzle, expr.components);
      place.swizzle_base = base.swizzle.empty() ? base.text : base.swizzle_base;
      place.text = place.swizzle_base + "." + letters(place.swizzle);
      return place;
    }
    case ExprKind::Index: {
      const LValue base = lvalue(expr.operands[0], pre);
      const Type& base_type = expr.operands[0].type;
      const std::string i = index_text(expr.operands[1], pre);
      place.variable = base.variable;
      const bool constant = expr.operands[1].kind == ExprKind::Constant;
      if (base_type.is_array() || base_type.is_matrix()) {
        const int count = base_type.is_array() ? base_type.array_size : base_type.columns;
        const std::string at = constant ? i : fmt::format("min(max({}, 0), {})", i, count - 1);
        place.text = fmt::format("{}.{}[{}]", base.text, base_type.is_array() ? "e" : "c", at);
      } else if (constant) {
        const int c = std::stoi(i);
        place.swizzle = base.swizzle.empty() ? std::vector<int>{c} : std::vector<int>{base.swizzle[c]};
        place.swizzle_base = base.swizzle.empty() ? base.text : base.swizzle_base;
        place.text = place.swizzle_base + "." + letters(place.swizzle);
      } else {
        place.dynamic_component = true;
        place.text = base.text;
        place.index = i;
        place.vector_type = base_type;
      }
      return place;
    }
    default:
      throw std::logic_error("opencl translation: not an lvalue");
  }
}

std::string FunctionEmitter::read(const LValue& place) {
  if (!place.dynamic_component) return place.text;
  return fmt::format("{}({}, {})", vector_at_helper(scope_, place.vector_type), place.text, place.index);
}

std::string FunctionEmitter::write(const LValue& place, const std::string& value) {
  if (!place.dynamic_component) return fmt::format("{} = {}", place.text, value);
  return fmt::format("{0} = {1}({0}, {2}, {3})", place.text, vector_with_helper(scope_, place.vector_type), place.index,
                     value);
}

namespace {

bool componentwise_float(const Type& type) { return type.scalar == Scalar::Float && !type.is_matrix(); }

}  // namespace

Value FunctionEmitter::assignment(const Expr& expr, Lines& pre, bool discarded) {
  const Expr& target = expr.operands[0];
  const Expr& source = expr.operands[1];
  const LValue place = lvalue(target, pre);
  const bool source_effects = has_effects(source);
  std::string written;
  if (!expr.compound) {
    Lines source_pre;
    Value value = emit(source, source_pre);
    pre.insert(pre.end(), source_pre.begin(), source_pre.end());
    // The helper that writes a dynamic component reads the vector: after the source's effects.
    if (place.dynamic_component && source_effects) value = temporary(value, source.type, pre);
    written = write(place, value.text);
  } else {
    // GLSL reads the target before evaluating the source.
    Value current{read(place)};
    Lines source_pre;
    Value value = emit(source, source_pre);
    if (source_effects || !source_pre.empty()) current = temporary(current, target.type, pre);
    pre.insert(pre.end(), source_pre.begin(), source_pre.end());
    if (place.dynamic_component && source_effects) value = temporary(value, source.type, pre);
    const bool c_compound = componentwise_float(target.type) && componentwise_float(source.type) &&
                            !place.dynamic_component && !current.stable &&
                            (expr.op == Operator::Add || expr.op == Operator::Subtract ||
                             expr.op == Operator::Multiply || expr.op == Operator::Divide);
    if (c_compound) {
      const char* symbol = expr.op == Operator::Add        ? "+="
                           : expr.op == Operator::Subtract ? "-="
                           : expr.op == Operator::Multiply ? "*="
                                                           : "/=";
      written = fmt::format("{} {} {}", place.text, symbol, value.text);
    } else {
      written = write(place, arithmetic(expr.op, target.type, current, target.type, value, source.type).text);
    }
  }
  if (discarded) return Value{written, kAssignment};
  if (place.dynamic_component) return Value{fmt::format("({}, {})", written, read(place))};
  return Value{written, kAssignment};
}

Value FunctionEmitter::increment(const Expr& expr, Lines& pre, bool discarded) {
  const Expr& target = expr.operands[0];
  const LValue place = lvalue(target, pre);
  const bool up = expr.op == Operator::PreIncrement || expr.op == Operator::PostIncrement;
  const bool post = expr.op == Operator::PostIncrement || expr.op == Operator::PostDecrement;
  const Type scalar{target.type.scalar};
  const Value one{scope_.scalar_literal(1.0, target.type.scalar), kPostfix, true};
  const Operator op = up ? Operator::Add : Operator::Subtract;
  if (post && !discarded) {
    const Value old = temporary(Value{read(place)}, target.type, pre);
    pre.push_back(write(place, arithmetic(op, target.type, old, target.type, one, scalar).text) + ";");
    return old;
  }
  std::string written;
  if (componentwise_float(target.type) && !place.dynamic_component) {
    written = fmt::format("{} {}= {}", place.text, up ? "+" : "-", one.text);
  } else {
    written = write(place, arithmetic(op, target.type, Value{read(place)}, target.type, one, scalar).text);
  }
  if (discarded) return Value{written, kAssignment};
  if (place.dynamic_component) return Value{fmt::format("({}, {})", written, read(place))};
  return Value{written, kAssignment};
}

Value FunctionEmitter::convert(const Value& value, const Type& from, Scalar to) {
  if (from.scalar == to) return value;
  const bool vector = from.rows > 1;
  const std::string n = vector ? std::to_string(from.rows) : "";
  const std::string& v = value.text;
  switch (to) {
    case Scalar::Float:
      if (vector) return Value{fmt::format("convert_{}{}({})", scope_.real(), n, v)};
      return Value{fmt::format("({}){}", scope_.real(), parenthesised(v, value.precedence, kUnary)), kUnary};
    case Scalar::Int:
      // As the interpreter: truncation, saturating, NaN to 0 (GLSL leaves those undefined).
      if (from.scalar == Scalar::Float) return Value{fmt::format("convert_int{}_sat_rtz({})", n, v)};
      if (from.scalar == Scalar::Uint) return Value{fmt::format("as_int{}({})", n, v)};
      // bvecN is already intN of 0 and 1.
      return vector ? value : Value{std::string("(int)") + parenthesised(v, value.precedence, kUnary), kUnary};
    case Scalar::Uint:
      if (from.scalar == Scalar::Float) return Value{fmt::format("{}({})", float_to_uint_helper(scope_, from), v)};
      if (vector || from.scalar == Scalar::Int) return Value{fmt::format("as_uint{}({})", n, v)};
      return Value{std::string("(uint)") + parenthesised(v, value.precedence, kUnary), kUnary};
    case Scalar::Bool: {
      const std::string zero = scope_.scalar_literal(0.0, from.scalar == Scalar::Bool ? Scalar::Int : from.scalar);
      const std::string test = fmt::format("{} != {}", parenthesised(v, value.precedence, kRelational), zero);
      // Vector comparisons give -1 for true.
      if (vector) return Value{fmt::format("-convert_int{}({})", n, test), kUnary};
      return Value{test, kEquality};
    }
    case Scalar::Void:
      break;
  }
  throw std::logic_error("opencl translation: conversion to void");
}

Value FunctionEmitter::construct(const Expr& expr, Lines& pre) {
  const Type& target = expr.type;
  std::vector<const Expr*> operands;
  for (const Expr& operand : expr.operands) operands.push_back(&operand);
  std::vector<Value> values = in_order(operands, pre);
  std::vector<Type> types;
  const bool converts = !target.is_struct() && !target.is_array();
  for (size_t i = 0; i < values.size(); ++i) {
    Type type = operands[i]->type;
    if (converts && type.scalar != target.scalar) {
      values[i] = convert(values[i], type, target.scalar);
      type.scalar = target.scalar;
    }
    types.push_back(type);
  }
  if (values.size() == 1 && types[0] == target) return values[0];
  if (values.size() == 1 && !types[0].is_matrix() && (is_single_scalar(target) || is_single_vector(target))) {
    const Value& v = values[0];
    if (target.is_scalar()) return Value{parenthesised(v.text, v.precedence, kPostfix) + ".x"};
    if (types[0].is_scalar()) return Value{fmt::format("({})({})", scope_.type(target), v.text), kUnary};
    std::vector<int> first(target.rows);
    for (int i = 0; i < target.rows; ++i) first[i] = i;
    return Value{parenthesised(v.text, v.precedence, kPostfix) + "." + letters(first)};
  }
  if (is_single_vector(target)) {
    int components = 0;
    bool plain = true;
    for (const Type& type : types) {
      components += type.components();
      plain = plain && !type.is_matrix();
    }
    if (plain && components == target.rows) {
      std::vector<std::string> parts;
      for (size_t i = 0; i < values.size(); ++i) {
        // A bool scalar into a bvec's intN.
        const bool boolean = types[i].is_scalar() && types[i].scalar == Scalar::Bool;
        parts.push_back(boolean ? std::string("(int)") + parenthesised(values[i].text, values[i].precedence, kUnary)
                                : values[i].text);
      }
      return Value{fmt::format("({})({})", scope_.type(target), fmt::join(parts, ", ")), kUnary};
    }
  }
  std::vector<std::string> texts;
  for (const Value& v : values) texts.push_back(v.text);
  return Value{fmt::format("{}({})", constructor_helper(scope_, target, types), fmt::join(texts, ", "))};
}

Value FunctionEmitter::call(const Expr& expr, Lines& pre) {
  const Function& function = scope_.module().functions[expr.function];
  std::vector<const Expr*> arguments;
  for (const Expr& argument : expr.operands) arguments.push_back(&argument);
  std::vector<ParameterQualifier> qualifiers;
  for (int parameter : function.parameters) qualifiers.push_back(scope_.module().variables[parameter].qualifier);
  std::vector<std::string> leading;
  if (info_.needs_globals[expr.function]) leading.push_back(globals_);
  return call_with_places(info_.function_names[expr.function], leading, arguments, qualifiers, expr.type, pre);
}

Value FunctionEmitter::call_with_places(const std::string& callee, const std::vector<std::string>& leading,
                                        const std::vector<const Expr*>& arguments,
                                        const std::vector<ParameterQualifier>& qualifiers, const Type& result,
                                        Lines& pre) {
  const size_t n = arguments.size();
  std::vector<Lines> hoisted(n);
  std::vector<Value> values(n);
  std::vector<bool> effects(n);
  std::vector<Type> types(n);
  std::vector<LValue> places(n);
  std::vector<std::string> copies(n);
  for (size_t i = 0; i < n; ++i) {
    const Expr& argument = *arguments[i];
    effects[i] = has_effects(argument);
    types[i] = argument.type;
    if (qualifiers[i] == ParameterQualifier::In) {
      values[i] = emit(argument, hoisted[i]);
      continue;
    }
    places[i] = lvalue(argument, hoisted[i]);
    // A variable passed to two out or inout parameters must see GLSL's copies, written back in
    // order; otherwise a plain variable passes by address.
    bool shared = false;
    for (size_t j = 0; j < n; ++j) {
      shared = shared || (j != i && qualifiers[j] != ParameterQualifier::In &&
                          arguments[j]->kind == ExprKind::Variable && arguments[j]->variable == places[i].variable);
    }
    if (places[i].plain_variable && argument.kind == ExprKind::Variable && !shared) {
      values[i] = Value{places[i].address, kPostfix, true};
      continue;
    }
    // Copied in at the call (inout), copied back after it returns.
    copies[i] = temporary_name();
    hoisted[i].push_back(qualifiers[i] == ParameterQualifier::InOut
                             ? fmt::format("{} {} = {};", scope_.type(argument.type), copies[i], read(places[i]))
                             : fmt::format("{} {};", scope_.type(argument.type), copies[i]));
    values[i] = Value{std::string("&") + copies[i], kUnary, true};
  }
  order_operands(hoisted, values, effects, types, pre,
                 [this](const Value& v, const Type& t, Lines& lines) { return temporary(v, t, lines); });
  std::vector<std::string> texts = leading;
  for (const Value& v : values) texts.push_back(v.text);
  const std::string text = fmt::format("{}({})", callee, fmt::join(texts, ", "));
  Lines copy_back;
  for (size_t i = 0; i < n; ++i) {
    if (!copies[i].empty()) copy_back.push_back(write(places[i], copies[i]) + ";");
  }
  if (copy_back.empty()) return Value{text};
  Value value;
  if (result.is_void()) {
    pre.push_back(text + ";");
  } else {
    value = temporary(Value{text}, result, pre);
  }
  pre.insert(pre.end(), copy_back.begin(), copy_back.end());
  return value;
}

}  // namespace clmarch::glsl::opencl

// The packet translation (opencl_packets.hpp). Each GLSL value is a list of component texts: a
// float, vector or matrix one text per component (column-major), each of type vfloat, or `real`
// where it does not depend on the point (a constant, iTime); an int or bool one C scalar. Results
// of arithmetic are bound to `const vfloat` temporaries as they are made, so every text is a name
// or a literal and may be read any number of times; the compiler folds the copies.
#include "glsl/opencl_packets.hpp"

#include "glsl/opencl_emitter.hpp"
#include "glsl/opencl_helpers.hpp"
#include "glsl/opencl_scope.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <utility>

namespace clmarch::glsl {
namespace {

using opencl::is_single_scalar;
using opencl::Lines;
using opencl::Scope;
using opencl::Writer;

/// Thrown where the module leaves the packet subset; the caller keeps the lane-at-a-time path.
struct Unsupported {
  std::string reason;
};

[[noreturn]] void unsupported(const SourceLocation& at, const std::string& what) {
  throw Unsupported{fmt::format("line {}: {}", at.line, what)};
}

/// Floats, vectors and matrices of floats: one lane vector per component.
bool is_real(const Type& type) { return type.scalar == Scalar::Float && !type.is_struct() && !type.is_array(); }

/// Ints, uints and bools that are not vectors: C scalars, the same on every lane.
bool is_uniform_scalar(const Type& type) {
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

// A condition in its parentheses: as it is where one pair already holds all of it (clang warns of
// `if ((a == b))`), else wrapped.
std::string in_parentheses(const std::string& text) {
  int depth = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    depth += text[i] == '(' ? 1 : text[i] == ')' ? -1 : 0;
    if (depth == 0 && i + 1 < text.size()) return "(" + text + ")";
  }
  return text.front() == '(' ? text : "(" + text + ")";
}

bool is_increment(Operator op) {
  return op == Operator::PreIncrement || op == Operator::PreDecrement || op == Operator::PostIncrement ||
         op == Operator::PostDecrement;
}

/// One function's body as packet code.
class PacketEmitter {
 public:
  /// globals_type: the C struct of the shader's globals, which every function gets by pointer
  /// (`globals`); empty where the module has none.
  PacketEmitter(Scope& scope, const std::vector<std::string>& names, const std::vector<std::string>& return_types,
                const std::string& globals_type)
      : scope_(scope),
        module_(scope.module()),
        names_(names),
        return_types_(return_types),
        globals_type_(globals_type) {}

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
  PacketValue arithmetic(Operator op, const Type& result, const PacketValue& a, const PacketValue& b,
                         const SourceLocation& at, Lines& pre);
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
  const std::vector<std::string>& names_;
  const std::vector<std::string>& return_types_;
  const std::string& globals_type_;
  std::map<int, std::string> local_names_;
  std::vector<std::string> used_names_;
  std::vector<bool> out_parameter_ = std::vector<bool>(module_.variables.size(), false);
  const Function* function_ = nullptr;
  int function_index_ = -1;
  int temporaries_ = 0;
  int loops_ = 0;
};

std::string PacketEmitter::packet(const PacketValue& value, size_t i) {
  const std::string& text = component(value, i);
  return value.kind == Kind::Uniform ? fmt::format("(vfloat)({})", text) : text;
}

std::string PacketEmitter::temporary(const std::string& type, const std::string& text, Lines& pre) {
  const std::string name = fmt::format("tmp{}", temporaries_++);
  pre.push_back(fmt::format("const {} {} = {};", type, name, text));
  return name;
}

PacketValue PacketEmitter::bound(PacketValue value, Lines& pre) {
  if (value.kind == Kind::Uniform) return value;
  for (std::string& text : value.c) text = temporary(value.kind == Kind::Mask ? "vint" : "vfloat", text, pre);
  value.stable = true;
  return value;
}

PacketValue PacketEmitter::stabilised(PacketValue value, const Type& type, Lines& pre) {
  if (value.stable) return value;
  if (value.kind != Kind::Uniform) return bound(std::move(value), pre);
  const std::string c_type = is_real(type) ? "real" : c_scalar(type.scalar);
  for (std::string& text : value.c) text = temporary(c_type, text, pre);
  value.stable = true;
  return value;
}

std::string PacketEmitter::name_of(int variable) {
  const Storage storage = module_.variables[variable].storage;
  if (storage == Storage::Global || storage == Storage::GlobalConst)
    return "globals->" + module_.variables[variable].name + "_";
  auto found = local_names_.find(variable);
  if (found != local_names_.end()) return found->second;
  const std::string& glsl = module_.variables[variable].name;
  std::string name = glsl + "_";
  for (int n = 2; std::find(used_names_.begin(), used_names_.end(), name) != used_names_.end(); ++n) {
    name = fmt::format("{}_{}", glsl, n);
  }
  used_names_.push_back(name);
  return local_names_[variable] = name;
}

// A scalar is its name; a vector's or matrix's component i is the name with c<i> (no GLSL name
// ends in an underscore followed by c and digits that another variable's name would produce).
std::string PacketEmitter::component_name(int variable, int i) {
  const std::string name = name_of(variable);
  const std::string text = module_.variables[variable].type.components() == 1 ? name : fmt::format("{}c{}", name, i);
  return out_parameter_[variable] ? fmt::format("(*{})", text) : text;
}

bool PacketEmitter::has_effects(const Expr& expr) const {
  if (expr.kind == ExprKind::Assign) return true;
  if (expr.kind == ExprKind::Operation && is_increment(expr.op)) return true;
  if (expr.kind == ExprKind::Call) {
    for (int parameter : module_.functions[expr.function].parameters) {
      if (module_.variables[parameter].qualifier != ParameterQualifier::In) return true;
    }
  }
  return std::any_of(expr.operands.begin(), expr.operands.end(), [&](const Expr& e) { return has_effects(e); });
}

void PacketEmitter::function(int index, Writer& out) {
  const Function& function = module_.functions[index];
  function_ = &function;
  function_index_ = index;
  std::vector<std::string> parameters{"real iTime"};
  if (!globals_type_.empty()) parameters.push_back(globals_type_ + "* globals");
  for (int parameter : function.parameters) {
    const Variable& variable = module_.variables[parameter];
    const bool by_address = variable.qualifier != ParameterQualifier::In;
    if (!is_real(variable.type) && !is_uniform_scalar(variable.type)) {
      unsupported(variable.location, fmt::format("parameter '{}' of a type other than float, vectors, matrices, "
                                                 "int, uint and bool",
                                                 variable.name));
    }
    const std::string type = is_real(variable.type) ? "vfloat" : c_scalar(variable.type.scalar);
    for (int i = 0; i < variable.type.components(); ++i) {
      parameters.push_back(fmt::format("{}{} {}", type, by_address ? "*" : "", component_name(parameter, i)));
    }
    out_parameter_[parameter] = by_address;
  }
  out.line(fmt::format("{} {}({}) {{", return_types_[index], names_[index], fmt::join(parameters, ", ")),
           function.location.line);
  out.indent();
  for (const Stmt& stmt : function.body.body) statement(stmt, out);
  out.outdent();
  out.line("}");
}

void PacketEmitter::statement(const Stmt& stmt, Writer& out) {
  const int line = stmt.location.line;
  Lines pre;
  switch (stmt.kind) {
    case StmtKind::Expression:
      emit(stmt.expression, pre);
      out.lines(pre, line);
      return;
    case StmtKind::Declaration:
      declaration(stmt, out);
      return;
    case StmtKind::Block:
      out.line("{", line);
      out.indent();
      for (const Stmt& s : stmt.body) statement(s, out);
      out.outdent();
      out.line("}");
      return;
    case StmtKind::If: {
      const PacketValue condition = emit(stmt.expression, pre);
      out.lines(pre, line);
      if (condition.kind == Kind::Mask) {
        masked_if(stmt, condition.c[0], out);
        return;
      }
      out.line(fmt::format("if {} {{", in_parentheses(condition.c[0])), line);
      out.indent();
      statement(stmt.body[0], out);
      out.outdent();
      if (stmt.body.size() > 1) {
        out.line("} else {");
        out.indent();
        statement(stmt.body[1], out);
        out.outdent();
      }
      out.line("}");
      return;
    }
    case StmtKind::Loop:
      loop(stmt, out);
      return;
    case StmtKind::Switch: {
      const PacketValue condition = emit(stmt.expression, pre);
      if (condition.kind != Kind::Uniform) unsupported(stmt.location, "a switch on a value of the point");
      out.lines(pre, line);
      out.line(fmt::format("switch {} {{", in_parentheses(condition.c[0])), line);
      out.indent();
      for (const Stmt& s : stmt.body) statement(s, out);
      out.outdent();
      out.line("}");
      return;
    }
    case StmtKind::Case:
      // The empty statement after the label lets a declaration follow it in C.
      if (stmt.has_value) {
        out.line(fmt::format("case {}:;",
                             scope_.scalar_literal(stmt.expression.constant.at(0), stmt.expression.type.scalar)),
                 line);
      } else {
        out.line("default:;", line);
      }
      return;
    case StmtKind::Return: {
      if (!stmt.has_value) {
        out.line("return;", line);
        return;
      }
      const PacketValue value = emit(stmt.expression, pre);
      out.lines(pre, line);
      const Type& type = function_->return_type;
      if (!is_real(type)) {
        out.line(fmt::format("return {};", value.c[0]), line);
      } else if (type.components() == 1) {
        out.line(fmt::format("return {};", packet(value, 0)), line);
      } else {
        std::vector<std::string> components;
        for (int i = 0; i < type.components(); ++i) components.push_back(packet(value, i));
        out.line(fmt::format("return ({}){{{{{}}}}};", return_types_[function_index_], fmt::join(components, ", ")),
                 line);
      }
      return;
    }
    case StmtKind::Break:
      out.line("break;", line);
      return;
    case StmtKind::Continue:
      out.line("continue;", line);
      return;
  }
}

/// What a branch of an `if` on the point writes and declares, and whether it leaves the branch.
struct BranchWrites {
  std::set<int> written;
  std::set<int> declared;
  const Stmt* leaves = nullptr;
};

void collect_writes(const Module& module, const Expr& expr, BranchWrites& writes) {
  if (expr.kind == ExprKind::Assign || (expr.kind == ExprKind::Operation && is_increment(expr.op))) {
    writes.written.insert(root_variable(expr.operands[0]));
  }
  if (expr.kind == ExprKind::Call) {
    const Function& callee = module.functions[expr.function];
    for (size_t i = 0; i < callee.parameters.size(); ++i) {
      if (module.variables[callee.parameters[i]].qualifier != ParameterQualifier::In) {
        writes.written.insert(root_variable(expr.operands[i]));
      }
    }
  }
  for (const Expr& operand : expr.operands) collect_writes(module, operand, writes);
}

// loops: the loops (and, for break, switches) around the statement inside the branch.
void collect_writes(const Module& module, const Stmt& stmt, BranchWrites& writes, int loops, int breakables) {
  switch (stmt.kind) {
    case StmtKind::Return:
      writes.leaves = &stmt;
      break;
    case StmtKind::Break:
      if (breakables == 0) writes.leaves = &stmt;
      break;
    case StmtKind::Continue:
      if (loops == 0) writes.leaves = &stmt;
      break;
    case StmtKind::Declaration:
      writes.declared.insert(stmt.variable);
      break;
    default:
      break;
  }
  if (stmt.has_value || stmt.kind == StmtKind::Expression || stmt.kind == StmtKind::If ||
      stmt.kind == StmtKind::Switch || (stmt.kind == StmtKind::Loop && stmt.has_condition)) {
    collect_writes(module, stmt.expression, writes);
  }
  if (stmt.has_step) collect_writes(module, stmt.step, writes);
  const bool loop = stmt.kind == StmtKind::Loop;
  const bool breakable = loop || stmt.kind == StmtKind::Switch;
  for (const Stmt& s : stmt.body)
    collect_writes(module, s, writes, loops + (loop ? 1 : 0), breakables + (breakable ? 1 : 0));
}

// An `if` on the point runs both branches on every lane, as a GPU's lanes do: each branch keeps the
// values it writes only in the lanes that take it (select() against a copy from before it), so
// the else branch reads, in its own lanes, what the if found. A branch that returns, breaks or
// continues, or writes an int or bool, would need control flow per lane: it keeps the lane path.
void PacketEmitter::masked_if(const Stmt& stmt, const std::string& mask, Writer& out) {
  BranchWrites writes;
  for (const Stmt& body : stmt.body) collect_writes(module_, body, writes, 0, 0);
  if (writes.leaves != nullptr) {
    unsupported(writes.leaves->location, "a return, break or continue in an if whose condition depends on the point");
  }
  std::vector<int> written;
  for (int variable : writes.written) {
    if (writes.declared.count(variable) != 0) continue;
    if (!is_real(module_.variables[variable].type)) {
      unsupported(stmt.location,
                  fmt::format("'{}', an int or bool written in an if whose condition depends on the point",
                              module_.variables[variable].name));
    }
    written.push_back(variable);
  }
  masked_branch(stmt.body[0], written, mask, out);
  if (stmt.body.size() > 1) {
    const std::string other = fmt::format("tmp{}", temporaries_++);
    out.line(fmt::format("const vint {} = ~{};", other, mask), stmt.location.line);
    masked_branch(stmt.body[1], written, other, out);
  }
}

void PacketEmitter::masked_branch(const Stmt& body, const std::vector<int>& written, const std::string& mask,
                                  Writer& out) {
  out.line("{", body.location.line);
  out.indent();
  std::vector<std::pair<std::string, std::string>> kept;
  for (int variable : written) {
    for (int i = 0; i < module_.variables[variable].type.components(); ++i) {
      const std::string place = component_name(variable, i);
      const std::string before = fmt::format("tmp{}", temporaries_++);
      out.line(fmt::format("const vfloat {} = {};", before, place), body.location.line);
      kept.emplace_back(place, before);
    }
  }
  statement(body, out);
  for (const auto& [place, before] : kept) out.line(fmt::format("{0} = select({1}, {0}, {2});", place, before, mask));
  out.outdent();
  out.line("}");
}

// Every loop as `for (first = 1;; first = 0)`: the step (a for's) or the test (a do-while's) runs
// at the top of every pass but the first, so a `continue` reaches them as GLSL's does, and their
// statements (calls, writes through temporaries) have a place to go.
void PacketEmitter::loop(const Stmt& stmt, Writer& out) {
  const int line = stmt.location.line;
  const std::string first = fmt::format("first{}", loops_++);
  auto test = [&](Writer& w) {
    if (!stmt.has_condition) return;
    Lines pre;
    const PacketValue condition = emit(stmt.expression, pre);
    if (condition.kind != Kind::Uniform) unsupported(stmt.location, "a loop whose end depends on the point");
    w.lines(pre, line);
    w.line(fmt::format("if (!{}) break;", in_parentheses(condition.c[0])), line);
  };
  out.line(fmt::format("for (int {0} = 1;; {0} = 0) {{", first), line);
  out.indent();
  if (stmt.has_step || !stmt.test_first) {
    out.line(fmt::format("if (!{}) {{", first), line);
    out.indent();
    if (stmt.has_step) {
      Lines pre;
      emit(stmt.step, pre);
      out.lines(pre, line);
    }
    if (!stmt.test_first) test(out);
    out.outdent();
    out.line("}", line);
  }
  if (stmt.test_first) test(out);
  statement(stmt.body[0], out);
  out.outdent();
  out.line("}");
}

void PacketEmitter::global_initialisers(Writer& out) {
  for (const Stmt& stmt : module_.globals) {
    const Variable& variable = module_.variables[stmt.variable];
    Lines pre;
    PacketValue value;
    if (stmt.has_value) {
      value = emit(stmt.expression, pre);
    } else {
      value.c.assign(1, is_real(variable.type) ? literal(0.0) : "0");
    }
    std::vector<std::string> targets;
    for (int i = 0; i < variable.type.components(); ++i) targets.push_back(component_name(stmt.variable, i));
    store(targets, variable.type, value, pre);
    out.lines(pre, stmt.location.line);
  }
}

void PacketEmitter::declaration(const Stmt& stmt, Writer& out) {
  const Variable& variable = module_.variables[stmt.variable];
  const int line = stmt.location.line;
  if (!is_real(variable.type) && !is_uniform_scalar(variable.type)) {
    unsupported(stmt.location,
                fmt::format("'{}', of a type other than float, vectors, matrices, int, uint and bool", variable.name));
  }
  Lines pre;
  PacketValue value;
  if (stmt.has_value) {
    value = emit(stmt.expression, pre);
    if (value.kind == Kind::Mask) unsupported(stmt.location, fmt::format("bool '{}' of the point", variable.name));
  } else {
    value.c.assign(1, is_real(variable.type) ? literal(0.0) : "0");
  }
  out.lines(pre, line);
  const std::string type = is_real(variable.type) ? "vfloat" : c_scalar(variable.type.scalar);
  for (int i = 0; i < variable.type.components(); ++i) {
    const std::string initial = is_real(variable.type) ? packet(value, i) : component(value, i);
    out.line(fmt::format("{} {} = {};", type, component_name(stmt.variable, i), initial), line);
  }
}

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
      return arithmetic(op, expr.type, operands[0], operands[1], expr.location, pre);
  }
}

PacketValue PacketEmitter::arithmetic(Operator op, const Type& result, const PacketValue& a, const PacketValue& b,
                                      const SourceLocation& at, Lines& pre) {
  const size_t n = std::max(a.c.size(), b.c.size());
  const bool integer = result.scalar == Scalar::Int || result.scalar == Scalar::Uint;
  PacketValue value{{}, a.kind == Kind::Packet || b.kind == Kind::Packet ? Kind::Packet : Kind::Uniform, true};
  for (size_t i = 0; i < n; ++i) {
    const std::string& x = component(a, i);
    const std::string& y = component(b, i);
    const char* symbol = nullptr;
    switch (op) {
      case Operator::Add:
        symbol = "+";
        break;
      case Operator::Subtract:
        symbol = "-";
        break;
      case Operator::Multiply:
        symbol = "*";
        break;
      case Operator::Divide:
      case Operator::Modulo:
        if (integer) {
          // GLSL leaves a division by zero undefined; the helper keeps it from trapping.
          value.c.push_back(fmt::format("{}({}, {})", opencl::integer_divide_helper(scope_, op, result, result), x, y));
          continue;
        }
        symbol = "/";
        break;
      case Operator::BitwiseAnd:
        symbol = "&";
        break;
      case Operator::BitwiseOr:
        symbol = "|";
        break;
      case Operator::BitwiseXor:
        symbol = "^";
        break;
      case Operator::ShiftLeft:
      case Operator::ShiftRight:
        // GLSL leaves shifts past the width undefined; C's are undefined behaviour.
        value.c.push_back(fmt::format("{} {} ({} & 31)", x, op == Operator::ShiftLeft ? "<<" : ">>", y));
        continue;
      default:
        unsupported(at, "an operator of two operands other than arithmetic and bitwise ones");
    }
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
  const char* symbol = nullptr;
  switch (expr.op) {
    case Operator::Less:
      symbol = "<";
      break;
    case Operator::Greater:
      symbol = ">";
      break;
    case Operator::LessEqual:
      symbol = "<=";
      break;
    case Operator::GreaterEqual:
      symbol = ">=";
      break;
    case Operator::Equal:
      symbol = "==";
      break;
    default:
      symbol = "!=";
      break;
  }
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
  if (value.kind == Kind::Mask) unsupported(SourceLocation{}, "a bool of the point stored");
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
      value = arithmetic(expr.op, target.type, current, value, expr.location, pre);
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
      stabilised(arithmetic(up ? Operator::Add : Operator::Subtract, target.type, before, one, expr.location, pre),
                 target.type, pre);
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
  if (!globals_type_.empty()) arguments.emplace_back("globals");
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
  const std::string text = fmt::format("{}({})", names_[expr.function], fmt::join(arguments, ", "));
  const Type& result = callee.return_type;
  PacketValue value{{}, Kind::Packet, true};
  if (result.is_void()) {
    pre.push_back(text + ";");
  } else if (!is_real(result)) {
    value = PacketValue{{temporary(c_scalar(result.scalar), text, pre)}, Kind::Uniform, true};
  } else if (result.components() == 1) {
    value.c.push_back(temporary("vfloat", text, pre));
  } else {
    const std::string name = temporary(return_types_[expr.function], text, pre);
    for (int i = 0; i < result.components(); ++i) value.c.push_back(fmt::format("{}.c[{}]", name, i));
  }
  for (const auto& [targets, temporaries] : write_backs) {
    for (size_t i = 0; i < targets.size(); ++i) pre.push_back(fmt::format("{} = {};", targets[i], temporaries[i]));
  }
  return value;
}

PacketValue PacketEmitter::builtin(const Expr& expr, Lines& pre) {
  if (expr.builtin == Builtin::Modf) unsupported(expr.location, "modf");
  const std::vector<PacketValue> v = in_order(expr.operands, pre);
  for (const PacketValue& value : v) {
    if (value.kind == Kind::Mask) unsupported(expr.location, "a built-in of bools of the point");
  }
  for (const Expr& operand : expr.operands) {
    if (!is_real(operand.type) && expr.builtin != Builtin::Abs && expr.builtin != Builtin::Min &&
        expr.builtin != Builtin::Max && expr.builtin != Builtin::Clamp) {
      unsupported(expr.location, "a built-in of integers or bools");
    }
  }
  const bool uniform = std::all_of(v.begin(), v.end(), [](const PacketValue& x) { return x.kind == Kind::Uniform; });
  // An argument's component as the result's type wants it: a scalar where all are uniform.
  auto arg = [&](size_t k, size_t i) { return uniform ? component(v[k], i) : packet(v[k], i); };
  const size_t n = std::max<size_t>(1, static_cast<size_t>(is_real(expr.type) ? expr.type.components() : 1));
  auto each = [&](const std::function<std::string(size_t)>& text) {
    PacketValue value{{}, uniform ? Kind::Uniform : Kind::Packet, true};
    for (size_t i = 0; i < n; ++i) value.c.push_back(uniform ? fmt::format("({})", text(i)) : text(i));
    if (uniform) {
      value.stable = false;
      return value;
    }
    return bound(value, pre);
  };
  auto function = [&](const char* name) {
    return each([&](size_t i) {
      std::vector<std::string> texts;
      for (size_t k = 0; k < v.size(); ++k) texts.push_back(arg(k, i));
      return fmt::format("{}({})", name, fmt::join(texts, ", "));
    });
  };
  // A sum over the components of the first argument's size.
  const size_t width = v[0].c.size();
  auto sum = [&](const std::function<std::string(size_t)>& term) {
    std::vector<std::string> terms;
    for (size_t i = 0; i < width; ++i) terms.push_back(term(i));
    return fmt::format("{}", fmt::join(terms, " + "));
  };
  auto scalar = [&](const std::string& text) {
    return uniform ? PacketValue{{fmt::format("({})", text)}, Kind::Uniform, false}
                   : bound(PacketValue{{text}, Kind::Packet, true}, pre);
  };
  const std::string one = literal(1.0), zero = literal(0.0);
  switch (expr.builtin) {
    case Builtin::Radians:
      return function("radians");
    case Builtin::Degrees:
      return function("degrees");
    case Builtin::Sin:
      return function("sin");
    case Builtin::Cos:
      return function("cos");
    case Builtin::Tan:
      return function("tan");
    case Builtin::Asin:
      return function("asin");
    case Builtin::Acos:
      return function("acos");
    case Builtin::Atan:
      return function("atan");
    case Builtin::Atan2:
      return function("atan2");
    case Builtin::Sinh:
      return function("sinh");
    case Builtin::Cosh:
      return function("cosh");
    case Builtin::Tanh:
      return function("tanh");
    case Builtin::Asinh:
      return function("asinh");
    case Builtin::Acosh:
      return function("acosh");
    case Builtin::Atanh:
      return function("atanh");
    case Builtin::Pow:
      return function("pow");
    case Builtin::Exp:
      return function("exp");
    case Builtin::Log:
      return function("log");
    case Builtin::Exp2:
      return function("exp2");
    case Builtin::Log2:
      return function("log2");
    case Builtin::Sqrt:
      return function("sqrt");
    case Builtin::InverseSqrt:
      return function("rsqrt");
    case Builtin::Abs:
      if (expr.type.scalar == Scalar::Int)
        return PacketValue{{fmt::format("as_int(abs({}))", v[0].c[0])}, Kind::Uniform, false};
      return function("fabs");
    case Builtin::Sign:
      return function("sign");
    case Builtin::Floor:
      return function("floor");
    case Builtin::Trunc:
      return function("trunc");
    // Halves to even, as Mesa's llvmpipe and the lane-at-a-time translation round them.
    case Builtin::Round:
    case Builtin::RoundEven:
      return function("rint");
    case Builtin::Ceil:
      return function("ceil");
    case Builtin::Fract:
      return each([&](size_t i) { return fmt::format("{0} - floor({0})", arg(0, i)); });
    case Builtin::Mod:
      return each([&](size_t i) { return fmt::format("{0} - {1} * floor({0} / {1})", arg(0, i), arg(1, i)); });
    case Builtin::Min:
      return function("min");
    case Builtin::Max:
      return function("max");
    case Builtin::Clamp:
      return each([&](size_t i) { return fmt::format("min(max({}, {}), {})", arg(0, i), arg(1, i), arg(2, i)); });
    case Builtin::Mix:
      if (expr.operands[2].type.scalar == Scalar::Bool) unsupported(expr.location, "mix with a bool choice");
      return each(
          [&](size_t i) { return fmt::format("{0} * ({1} - {2}) + {3} * {2}", arg(0, i), one, arg(2, i), arg(1, i)); });
    case Builtin::Step:
      return each([&](size_t i) {
        return uniform ? fmt::format("{} < {} ? {} : {}", arg(1, i), arg(0, i), zero, one)
                       : fmt::format("select((vfloat)({}), (vfloat)({}), {} < {})", one, zero, arg(1, i), arg(0, i));
      });
    case Builtin::SmoothStep: {
      PacketValue t{{}, uniform ? Kind::Uniform : Kind::Packet, true};
      for (size_t i = 0; i < n; ++i) {
        const std::string text = fmt::format("min(max(({} - {}) / ({} - {}), {}), {})", arg(2, i), arg(0, i), arg(1, i),
                                             arg(0, i), zero, one);
        t.c.push_back(temporary(uniform ? "real" : "vfloat", text, pre));
      }
      return each(
          [&](size_t i) { return fmt::format("{0} * {0} * ({1} - {2} * {0})", t.c[i], literal(3.0), literal(2.0)); });
    }
    case Builtin::Length:
      return scalar(fmt::format("sqrt({})", sum([&](size_t i) { return fmt::format("{0} * {0}", arg(0, i)); })));
    case Builtin::Distance: {
      PacketValue d = arithmetic(Operator::Subtract, expr.operands[0].type, v[0], v[1], expr.location, pre);
      return scalar(fmt::format("sqrt({})", sum([&](size_t i) { return fmt::format("{0} * {0}", d.c[i]); })));
    }
    case Builtin::Dot:
      return scalar(sum([&](size_t i) { return fmt::format("{} * {}", arg(0, i), arg(1, i)); }));
    case Builtin::Cross:
      return each([&](size_t i) {
        const size_t j = (i + 1) % 3, k = (i + 2) % 3;
        return fmt::format("{} * {} - {} * {}", arg(0, j), arg(1, k), arg(0, k), arg(1, j));
      });
    case Builtin::Normalize: {
      const PacketValue length =
          scalar(fmt::format("sqrt({})", sum([&](size_t i) { return fmt::format("{0} * {0}", arg(0, i)); })));
      return each([&](size_t i) { return fmt::format("{} / {}", arg(0, i), length.c[0]); });
    }
    case Builtin::Reflect: {
      const PacketValue d = scalar(sum([&](size_t i) { return fmt::format("{} * {}", arg(1, i), arg(0, i)); }));
      return each(
          [&](size_t i) { return fmt::format("{} - {} * {} * {}", arg(0, i), literal(2.0), d.c[0], arg(1, i)); });
    }
    case Builtin::OuterProduct:
      return each([&](size_t i) {
        const size_t rows = static_cast<size_t>(expr.type.rows);
        return fmt::format("{} * {}", arg(0, i % rows), arg(1, i / rows));
      });
    case Builtin::MatrixCompMult:
      return each([&](size_t i) { return fmt::format("{} * {}", arg(0, i), arg(1, i)); });
    case Builtin::Transpose: {
      const Type& m = expr.operands[0].type;
      return each([&](size_t i) {
        const size_t column = i / m.columns, row = i % m.columns;
        return arg(0, row * m.rows + column);
      });
    }
    default:
      unsupported(expr.location, "this built-in function");
  }
}

}  // namespace

PacketTranslation translate_to_packets(const Module& module, const TranslationOptions& options) {
  TranslationOptions packet_options = options;
  packet_options.prefix = options.prefix + "_packet";
  Scope scope(module, packet_options);
  std::vector<std::string> names, return_types;
  for (size_t i = 0; i < module.functions.size(); ++i) {
    const Function& function = module.functions[i];
    names.push_back(scope.unique_name(fmt::format("{}{}", function.name, i)));
    const Type& result = function.return_type;
    if (result.is_void()) {
      return_types.emplace_back("void");
    } else if (is_real(result) && result.components() == 1) {
      return_types.emplace_back("vfloat");
    } else if (is_real(result)) {
      // A vector or matrix comes back as the components of a struct.
      return_types.push_back(
          scope.helper(fmt::format("components{}", result.components()), [&](const std::string& name) {
            return fmt::format("typedef struct {{ vfloat c[{}]; }} {};\n", result.components(), name);
          }));
    } else if (is_uniform_scalar(result)) {
      return_types.emplace_back(result.scalar == Scalar::Uint ? "uint" : "int");
    } else {
      return {"", fmt::format("line {}: function '{}' returns a struct or an array", function.location.line,
                              function.name)};
    }
  }
  // The globals, as the lane-at-a-time translation has them: a struct the entry point initialises.
  std::string globals_type;
  std::string members;
  for (const Stmt& global : module.globals) {
    const Variable& variable = module.variables[global.variable];
    if (!is_real(variable.type) && !is_uniform_scalar(variable.type)) {
      return {"", fmt::format("line {}: global '{}' of a type other than float, vectors, matrices, int, uint and bool",
                              variable.location.line, variable.name)};
    }
    for (int i = 0; i < variable.type.components(); ++i) {
      members += fmt::format("  {} {}_{};\n",
                             is_real(variable.type)                 ? "vfloat"
                             : variable.type.scalar == Scalar::Uint ? "uint"
                                                                    : "int",
                             variable.name, variable.type.components() == 1 ? "" : fmt::format("c{}", i));
    }
  }
  if (!members.empty()) {
    globals_type = scope.helper("globals", [&](const std::string& name) {
      return fmt::format("typedef struct {{\n{}}} {};\n", members, name);
    });
  }
  Writer functions(module.file_name);
  Writer initialisers(module.file_name);
  try {
    for (size_t i = 0; i < module.functions.size(); ++i) {
      PacketEmitter emitter(scope, names, return_types, globals_type);
      emitter.function(static_cast<int>(i), functions);
    }
    if (!globals_type.empty()) {
      initialisers.indent();
      initialisers.line(fmt::format("{} globals_value;", globals_type));
      initialisers.line(fmt::format("{}* globals = &globals_value;", globals_type));
      PacketEmitter(scope, names, return_types, globals_type).global_initialisers(initialisers);
    }
  } catch (const Unsupported& reason) {
    return {"", reason.reason};
  }
  const Function& distance = module.functions[module.distance_function];
  if (distance.parameters.size() != 1 || module.variables[distance.parameters[0]].qualifier != ParameterQualifier::In) {
    return {"", "the distance function's point is not an in parameter"};
  }
  const std::string prefix = options.prefix;
  std::string code;
  for (const std::string& definition : scope.definitions()) code += definition;
  code += functions.text();
  const std::string arguments = globals_type.empty() ? "iTime, x, y, z" : "iTime, globals, x, y, z";
  const std::string distance_value = distance.return_type.components() > 1 ? ".c[0]" : "";
  code += fmt::format("vfloat {}_distance_packet(vfloat x, vfloat y, vfloat z, real iTime) {{\n", prefix);
  code += initialisers.text();
  code += fmt::format("#line {} \"{}_packet (translated)\"\n", 1, prefix);
  code += fmt::format("  return {}({}){};\n}}\n", names[module.distance_function], arguments, distance_value);
  if (module.color_function >= 0) {
    code += fmt::format("vec3v {}_color_packet(vfloat x, vfloat y, vfloat z, real iTime) {{\n", prefix);
    code += initialisers.text();
    code += fmt::format("#line {} \"{}_packet (translated)\"\n", 1, prefix);
    code += fmt::format("  const {} c = {}({});\n  return (vec3v){{c.c[0], c.c[1], c.c[2]}};\n}}\n",
                        return_types[module.color_function], names[module.color_function], arguments);
  }
  return {code, ""};
}

}  // namespace clmarch::glsl

// Statements and functions of the packet translation (packet_emitter.hpp).
#include "glsl/packet_emitter.hpp"

#include <algorithm>
#include <optional>
#include <utility>

namespace clmarch::glsl::packets {

namespace {

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

}  // namespace

namespace {

void collect_expression_writes(const Module& module, const std::vector<std::set<int>>& globals_written,
                               const Expr& expr, Writes& writes) {
  if (expr.kind == ExprKind::Assign || (expr.kind == ExprKind::Operation && is_increment(expr.op))) {
    writes.written.insert(root_variable(expr.operands[0]));
  }
  if (expr.kind == ExprKind::Call) {
    const std::set<int>& globals = globals_written.at(expr.function);
    writes.written.insert(globals.begin(), globals.end());
    const Function& callee = module.functions[expr.function];
    for (size_t i = 0; i < callee.parameters.size(); ++i) {
      if (module.variables[callee.parameters[i]].qualifier != ParameterQualifier::In) {
        writes.written.insert(root_variable(expr.operands[i]));
      }
    }
  }
  for (const Expr& operand : expr.operands) collect_expression_writes(module, globals_written, operand, writes);
}

bool names(const Expr& expr, int variable) {
  if (expr.kind == ExprKind::Variable && expr.variable == variable) return true;
  return std::any_of(expr.operands.begin(), expr.operands.end(), [&](const Expr& e) { return names(e, variable); });
}

// The expressions a statement itself holds (not those of the statements in its body).
std::vector<const Expr*> own_expressions(const Stmt& stmt) {
  std::vector<const Expr*> expressions;
  if (stmt.has_value || stmt.kind == StmtKind::Expression || stmt.kind == StmtKind::If ||
      stmt.kind == StmtKind::Switch || (stmt.kind == StmtKind::Loop && stmt.has_condition)) {
    expressions.push_back(&stmt.expression);
  }
  if (stmt.has_step) expressions.push_back(&stmt.step);
  return expressions;
}

// Whether a statement of stmt outside `except` names the variable (a declaration without an
// initializer aside: it only zeroes it).
bool named_outside(const Stmt& stmt, const Stmt* except, int variable) {
  if (&stmt == except) return false;
  for (const Expr* expr : own_expressions(stmt)) {
    if (names(*expr, variable)) return true;
  }
  if (stmt.kind == StmtKind::Declaration && stmt.variable == variable && stmt.has_value) return true;
  return std::any_of(stmt.body.begin(), stmt.body.end(),
                     [&](const Stmt& s) { return named_outside(s, except, variable); });
}

// Whether the first use of the variable in stmt, in the order it runs, sets it from values that do
// not include it (`i = 0`, a declaration's initializer); nullopt where stmt does not name it.
std::optional<bool> first_use_defines(const Stmt& stmt, int variable) {
  if (stmt.kind == StmtKind::Block) {
    for (const Stmt& s : stmt.body) {
      if (const std::optional<bool> first = first_use_defines(s, variable)) return first;
    }
    return std::nullopt;
  }
  if (stmt.kind == StmtKind::Declaration && stmt.variable == variable) {
    if (!stmt.has_value) return std::nullopt;
    return !names(stmt.expression, variable);
  }
  const Expr& expr = stmt.expression;
  if (stmt.kind == StmtKind::Expression && expr.kind == ExprKind::Assign && !expr.compound &&
      expr.operands[0].kind == ExprKind::Variable && expr.operands[0].variable == variable) {
    return !names(expr.operands[1], variable);
  }
  if (named_outside(stmt, nullptr, variable)) return false;
  return std::nullopt;
}

}  // namespace

void collect_writes(const Module& module, const std::vector<std::set<int>>& globals_written, const Stmt& stmt,
                    Writes& writes, int loops, int breakables) {
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
    collect_expression_writes(module, globals_written, stmt.expression, writes);
  }
  if (stmt.has_step) collect_expression_writes(module, globals_written, stmt.step, writes);
  const bool loop = stmt.kind == StmtKind::Loop;
  const bool breakable = loop || stmt.kind == StmtKind::Switch;
  for (const Stmt& s : stmt.body)
    collect_writes(module, globals_written, s, writes, loops + (loop ? 1 : 0), breakables + (breakable ? 1 : 0));
}

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
    if (!info_.globals_written[expr.function].empty()) return true;
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
  if (!info_.globals_type.empty()) parameters.push_back(info_.globals_type + "* globals");
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
  out.line(fmt::format("{} {}({}) {{", info_.return_types[index], info_.names[index], fmt::join(parameters, ", ")),
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
      if (value.kind == Kind::Mask) unsupported(stmt.location, "a bool of the point returned");
      if (!is_real(type)) {
        out.line(fmt::format("return {};", value.c[0]), line);
      } else if (type.components() == 1) {
        out.line(fmt::format("return {};", packet(value, 0)), line);
      } else {
        std::vector<std::string> components;
        for (int i = 0; i < type.components(); ++i) components.push_back(packet(value, i));
        out.line(
            fmt::format("return ({}){{{{{}}}}};", info_.return_types[function_index_], fmt::join(components, ", ")),
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

// An `if` on the point runs both branches on every lane, as a GPU's lanes do: each branch keeps the
// values it writes only in the lanes that take it (select() against a copy from before it), so
// the else branch reads, in its own lanes, what the if found. A branch that returns, breaks or
// continues, or writes an int or bool, would need control flow per lane: it keeps the lane path.
void PacketEmitter::masked_if(const Stmt& stmt, const std::string& mask, Writer& out) {
  Writes writes;
  for (const Stmt& body : stmt.body) collect_writes(module_, info_.globals_written, body, writes);
  if (writes.leaves != nullptr) {
    unsupported(writes.leaves->location, "a return, break or continue in an if whose condition depends on the point");
  }
  std::vector<int> written;
  for (int variable : writes.written) {
    if (writes.declared.count(variable) != 0) continue;
    if (!is_real(module_.variables[variable].type)) {
      // An int set afresh in the branch and used nowhere else (a loop's counter: its declaration
      // stands at the top of the function) holds the same on every lane that reads it.
      if (!named_outside(function_->body, &stmt, variable) &&
          std::all_of(stmt.body.begin(), stmt.body.end(),
                      [&](const Stmt& body) { return first_use_defines(body, variable).value_or(true); })) {
        continue;
      }
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
      if (value.kind == Kind::Mask) unsupported(stmt.location, fmt::format("global '{}' of the point", variable.name));
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

}  // namespace clmarch::glsl::packets

// Statements and function definitions of the OpenCL translation (opencl_emitter.hpp).
#include "glsl/opencl_emitter.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace clmarch::glsl::opencl {

namespace {

// The file name as a C string literal for #line.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c == '\n' || c == '\r' ? ' ' : c;
  }
  return out + "\"";
}

}  // namespace

Writer::Writer(const std::string& file_name) : quoted_file_(quoted(file_name)) {}

void Writer::line(const std::string& text, int user_line) {
  if (user_line > 0 && user_line != next_line_) {
    text_ += fmt::format("#line {} {}\n", user_line, quoted_file_);
    next_line_ = user_line;
  }
  text_ += std::string(indent_, ' ') + text + "\n";
  if (next_line_ > 0) ++next_line_;
}

void Writer::lines(const Lines& lines, int user_line) {
  for (const std::string& text : lines) line(text, user_line);
}

// Each declaration is its own variable: a name taken in the function is numbered, so that C's
// scopes (which begin before an initialiser, GLSL's after it) never matter.
std::string FunctionEmitter::local_name(int variable) {
  std::string& name = local_names_[variable];
  if (!name.empty()) return name;
  const std::string& glsl = scope_.module().variables[variable].name;
  name = glsl + "_";
  for (int n = 2; std::find(used_local_names_.begin(), used_local_names_.end(), name) != used_local_names_.end(); ++n) {
    name = fmt::format("{}_{}", glsl, n);
  }
  used_local_names_.push_back(name);
  return name;
}

void FunctionEmitter::function(int index, Writer& out) {
  const Function& function = scope_.module().functions[index];
  std::vector<std::string> parameters;
  if (info_.needs_globals[index]) parameters.push_back(info_.globals_type + "* globals");
  for (int parameter : function.parameters) {
    const Variable& variable = scope_.module().variables[parameter];
    const bool by_address = variable.qualifier != ParameterQualifier::In;
    out_parameter_[parameter] = by_address;
    parameters.push_back(
        fmt::format("{}{} {}", scope_.type(variable.type), by_address ? "*" : "", local_name(parameter)));
  }
  out.line(fmt::format("{} {}({}) {{", scope_.type(function.return_type), info_.function_names[index],
                       parameters.empty() ? "void" : fmt::format("{}", fmt::join(parameters, ", "))),
           function.location.line);
  out.indent();
  for (int parameter : function.parameters) {
    const Variable& variable = scope_.module().variables[parameter];
    // An out parameter starts undefined in GLSL; zero, as locals are.
    if (variable.qualifier == ParameterQualifier::Out) {
      out.line(fmt::format("*{} = {};", local_name(parameter), scope_.zero(variable.type)), function.location.line);
    }
  }
  block_body(function.body.body, out);
  // Falling off the end of a non-void function is undefined in GLSL (and warned about by C).
  const Stmt* last = &function.body;
  while (last->kind == StmtKind::Block && !last->body.empty()) last = &last->body.back();
  if (!function.return_type.is_void() && last->kind != StmtKind::Return) {
    out.line(fmt::format("return {};", scope_.zero(function.return_type)));
  }
  out.outdent();
  out.line("}");
}

void FunctionEmitter::global_initialisers(Writer& out) {
  for (const Stmt& stmt : scope_.module().globals) {
    const Variable& variable = scope_.module().variables[stmt.variable];
    Lines pre;
    const std::string value = stmt.has_value ? emit(stmt.expression, pre).text : scope_.zero(variable.type);
    out.lines(pre, stmt.location.line);
    out.line(fmt::format("{}->{}_ = {};", globals_, variable.name, value), stmt.location.line);
  }
}

void FunctionEmitter::block_body(const std::vector<Stmt>& body, Writer& out) {
  for (const Stmt& stmt : body) statement(stmt, out);
}

namespace {

// The statements of a branch or loop body, without the braces of a block.
const std::vector<Stmt>& inner(const Stmt& stmt, std::vector<Stmt>& single) {
  if (stmt.kind == StmtKind::Block) return stmt.body;
  single = {stmt};
  return single;
}

}  // namespace

void FunctionEmitter::statement(const Stmt& stmt, Writer& out) {
  const int line = stmt.location.line;
  std::vector<Stmt> single;
  switch (stmt.kind) {
    case StmtKind::Expression: {
      Lines lines;
      effect_statements(stmt.expression, lines);
      out.lines(lines, line);
      return;
    }
    case StmtKind::Declaration:
      declaration(stmt, out);
      return;
    // Every local has a name of its own in the function, so a block's braces change nothing.
    case StmtKind::Block:
      block_body(stmt.body, out);
      return;
    case StmtKind::If: {
      Lines pre;
      const Value condition = emit(stmt.expression, pre);
      out.lines(pre, line);
      out.line(fmt::format("if ({}) {{", condition.text), line);
      const Stmt* branch = &stmt;
      while (true) {
        out.indent();
        block_body(inner(branch->body[0], single), out);
        out.outdent();
        if (branch->body.size() < 2) break;
        const Stmt& otherwise = branch->body[1];
        if (otherwise.kind == StmtKind::If) {
          // else if, where the condition needs no statements of its own.
          Lines else_pre;
          const Value else_condition = emit(otherwise.expression, else_pre);
          if (else_pre.empty()) {
            out.line(fmt::format("}} else if ({}) {{", else_condition.text), otherwise.location.line);
            branch = &otherwise;
            continue;
          }
        }
        out.line("} else {");
        out.indent();
        block_body(inner(otherwise, single), out);
        out.outdent();
        break;
      }
      out.line("}");
      return;
    }
    case StmtKind::Loop:
      loop(stmt, out);
      return;
    case StmtKind::Switch: {
      Lines pre;
      const Value condition = emit(stmt.expression, pre);
      out.lines(pre, line);
      out.line(fmt::format("switch ({}) {{", condition.text), line);
      for (size_t i = 0; i < stmt.body.size(); ++i) {
        const Stmt& s = stmt.body[i];
        if (s.kind != StmtKind::Case) {
          out.indent();
          statement(s, out);
          out.outdent();
          continue;
        }
        // A C label precedes a statement, never a declaration or the end of the block.
        const bool empty_statement = i + 1 == stmt.body.size() || stmt.body[i + 1].kind == StmtKind::Declaration;
        const std::string label = s.has_value ? fmt::format("case {}:", emit(s.expression, pre).text) : "default:";
        out.line(label + (empty_statement ? ";" : ""), s.location.line);
      }
      out.line("}");
      return;
    }
    case StmtKind::Case:
      return;
    case StmtKind::Return: {
      Lines pre;
      if (!stmt.has_value) {
        out.line("return;", line);
      } else if (stmt.expression.type.is_void()) {
        effect_statements(stmt.expression, pre);
        out.lines(pre, line);
        out.line("return;", line);
      } else {
        const Value value = emit(stmt.expression, pre);
        out.lines(pre, line);
        out.line(fmt::format("return {};", value.text), line);
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

void FunctionEmitter::declaration(const Stmt& stmt, Writer& out) {
  const Variable& variable = scope_.module().variables[stmt.variable];
  std::string value;
  if (stmt.has_value) {
    Lines pre;
    value = emit(stmt.expression, pre).text;
    out.lines(pre, stmt.location.line);
  } else {
    // WebGL zero-initialises locals, and shaders rely on it.
    value = scope_.zero(variable.type);
  }
  out.line(fmt::format("{} {} = {};", scope_.type(variable.type), local_name(stmt.variable), value),
           stmt.location.line);
}

void FunctionEmitter::loop(const Stmt& stmt, Writer& out) {
  const int line = stmt.location.line;
  Lines condition_pre;
  const Value condition = stmt.has_condition ? emit(stmt.expression, condition_pre) : Value{};
  Lines step;
  if (stmt.has_step) effect_statements(stmt.step, step);
  std::vector<Stmt> single;
  const std::vector<Stmt>& body = inner(stmt.body[0], single);
  if (condition_pre.empty() && step.size() <= 1 && (stmt.test_first || step.empty())) {
    std::string step_text = step.empty() ? "" : step[0].substr(0, step[0].size() - 1);
    if (!stmt.test_first) {
      out.line("do {", line);
    } else if (step_text.empty() && stmt.has_condition) {
      out.line(fmt::format("while ({}) {{", condition.text), line);
    } else {
      out.line(fmt::format("for (; {}; {}) {{", condition.text, step_text), line);
    }
    out.indent();
    block_body(body, out);
    out.outdent();
    out.line(stmt.test_first ? "}" : fmt::format("}} while ({});", stmt.has_condition ? condition.text : "true"));
    return;
  }
  // The condition or the step needs statements: the loop tests and steps inside its body, the
  // step skipped on the first iteration, so that `continue` still runs it.
  const std::string first = fmt::format("first{}", ++temporaries_);
  out.line(fmt::format("for (int {0} = 1;; {0} = 0) {{", first), line);
  out.indent();
  Lines test = condition_pre;
  if (stmt.has_condition) test.push_back(fmt::format("if (!({})) break;", condition.text));
  Lines after_first = step;
  if (!stmt.test_first) after_first.insert(after_first.end(), test.begin(), test.end());
  if (!after_first.empty()) {
    out.line(fmt::format("if (!{}) {{", first), line);
    out.indent();
    out.lines(after_first, line);
    out.outdent();
    out.line("}");
  }
  if (stmt.test_first) out.lines(test, line);
  block_body(body, out);
  out.outdent();
  out.line("}");
}

void FunctionEmitter::effect_statements(const Expr& expr, Lines& out) {
  switch (expr.kind) {
    case ExprKind::Assign:
      out.push_back(assignment(expr, out, true).text + ";");
      return;
    case ExprKind::Comma:
      for (const Expr& operand : expr.operands) effect_statements(operand, out);
      return;
    case ExprKind::Call:
    case ExprKind::BuiltinCall:
      if (expr.kind == ExprKind::Call || expr.builtin == Builtin::Modf) {
        const Value value = emit(expr, out);
        // A value already in a temporary was computed by the statements emitted.
        if (!value.stable && !value.text.empty()) out.push_back(value.text + ";");
        return;
      }
      break;
    case ExprKind::Operation:
      if (expr.op == Operator::PreIncrement || expr.op == Operator::PreDecrement ||
          expr.op == Operator::PostIncrement || expr.op == Operator::PostDecrement) {
        out.push_back(increment(expr, out, true).text + ";");
        return;
      }
      if ((expr.op == Operator::LogicalAnd || expr.op == Operator::LogicalOr) && has_effects(expr.operands[1])) {
        const Value condition = emit(expr.operands[0], out);
        const bool is_and = expr.op == Operator::LogicalAnd;
        out.push_back(fmt::format(
            "if ({}) {{",
            is_and ? condition.text : std::string("!") + parenthesised(condition.text, condition.precedence, kUnary)));
        Lines right;
        effect_statements(expr.operands[1], right);
        for (const std::string& line : right) out.push_back(std::string("  ") + line);
        out.push_back("}");
        return;
      }
      break;
    case ExprKind::Select:
      if (has_effects(expr.operands[1]) || has_effects(expr.operands[2])) {
        const Value condition = emit(expr.operands[0], out);
        Lines then_lines;
        Lines else_lines;
        effect_statements(expr.operands[1], then_lines);
        effect_statements(expr.operands[2], else_lines);
        out.push_back(fmt::format("if ({}) {{", condition.text));
        for (const std::string& line : then_lines) out.push_back(std::string("  ") + line);
        if (!else_lines.empty()) {
          out.push_back("} else {");
          for (const std::string& line : else_lines) out.push_back(std::string("  ") + line);
        }
        out.push_back("}");
        return;
      }
      break;
    default:
      break;
  }
  // A value nobody reads: only its operands' side effects remain, in order.
  if (!has_effects(expr)) return;
  for (const Expr& operand : expr.operands) effect_statements(operand, out);
}

}  // namespace clmarch::glsl::opencl

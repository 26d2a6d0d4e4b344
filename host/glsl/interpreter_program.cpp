// Compiles a Module into the interpreter's Program: lays out the frame (every variable, then each
// node's slot and scratch) and checks what the evaluation relies on: no recursion, and the IR's
// shapes agreeing with each other.
#include "glsl/interpreter_program.hpp"

#include "glsl/interpreter_operators.hpp"

#include "common/errors.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace clmarch::glsl::interpreter {
namespace {

/// A broken promise of glsl_ir.hpp's contract: a bug of the front end, not the user's.
[[noreturn]] void contract_broken(const std::string& what) {
  throw std::logic_error("glsl interpreter: the IR breaks its contract: " + what);
}

class ProgramCompiler {
 public:
  explicit ProgramCompiler(const Module& module) : module_(module) {}

  Program compile() {
    Program program;
    program.file_name = module_.file_name;
    const int function_count = static_cast<int>(module_.functions.size());
    if (module_.distance_function < 0 || module_.distance_function >= function_count)
      contract_broken(fmt::format("distance_function {} of {} functions", module_.distance_function, function_count));
    if (module_.color_function >= function_count)
      contract_broken(fmt::format("color_function {} of {} functions", module_.color_function, function_count));
    for (const Variable& variable : module_.variables) {
      const int size = size_of(variable.type);
      variable_offsets_.push_back(allocate(size));
      if (variable.storage == Storage::Uniform)
        program.uniforms.push_back({variable_offsets_.back(), size, variable.uniform});
    }
    callees_.resize(module_.functions.size());
    for (const Stmt& global : module_.globals) program.globals.push_back(compile(global));
    for (int index = 0; index < function_count; ++index) {
      const Function& function = module_.functions[index];
      current_function_ = index;
      CompiledFunction compiled;
      compiled.name = function.name;
      compiled.return_size = size_of(function.return_type);
      for (int parameter : function.parameters) {
        const Variable& variable = module_.variables.at(parameter);
        compiled.parameters.push_back({variable_offsets_[parameter], size_of(variable.type), variable.qualifier});
      }
      compiled.body = compile(function.body);
      program.functions.push_back(std::move(compiled));
    }
    check_entry_point(module_.distance_function);
    if (module_.color_function >= 0) check_entry_point(module_.color_function);
    check_no_recursion();
    program.frame_size = frame_size_;
    program.place_count = place_count_;
    program.distance_function = module_.distance_function;
    program.color_function = module_.color_function;
    return program;
  }

 private:
  int size_of(const Type& type) const {
    if (type.is_array()) return type.array_size * size_of(type.element());
    if (type.is_struct()) {
      int size = 0;
      for (const StructMember& member : module_.structs.at(type.struct_index).members) size += size_of(member.type);
      return size;
    }
    return type.is_void() ? 0 : type.components();
  }

  int allocate(int size) {
    const int offset = frame_size_;
    frame_size_ += size;
    return offset;
  }

  /// Gives node a scratch for its earlier operands' values when a later operand has side effects:
  /// `a + (a = 2)` adds a's value from before the assignment, as left-to-right order says.
  void protect_operands(Node& node) {
    bool later_side_effects = false;
    for (std::size_t k = 1; k < node.operands.size(); ++k) later_side_effects |= node.operands[k].has_side_effects;
    if (!later_side_effects) return;
    int size = 0;
    for (std::size_t k = 0; k + 1 < node.operands.size(); ++k) size += node.operands[k].size;
    node.protects_operands = true;
    node.scratch = allocate(size);
  }

  Node compile(const Expr& expr) {
    Node node;
    node.kind = expr.kind;
    node.type = expr.type;
    node.location = expr.location;
    node.op = expr.op;
    node.compound = expr.compound;
    node.builtin = expr.builtin;
    node.size = size_of(expr.type);
    for (const Expr& operand : expr.operands) {
      node.operands.push_back(compile(operand));
      node.has_side_effects |= node.operands.back().has_side_effects;
    }
    switch (expr.kind) {
      case ExprKind::Constant:
        if (static_cast<int>(expr.constant.size()) != node.size)
          contract_broken(fmt::format("a constant of {} components for a type of {}", expr.constant.size(), node.size));
        node.constant = expr.constant;
        break;
      case ExprKind::Variable:
        if (expr.variable < 0 || expr.variable >= static_cast<int>(variable_offsets_.size()))
          contract_broken(fmt::format("variable {} of {}", expr.variable, variable_offsets_.size()));
        node.variable_offset = variable_offsets_[expr.variable];
        break;
      case ExprKind::Swizzle:
        for (int component : expr.components)
          if (component < 0 || component >= node.operands.at(0).size)
            contract_broken(fmt::format("swizzle component {} of {}", component, node.operands[0].size));
        node.components = expr.components;
        node.slot = allocate(node.size);
        break;
      case ExprKind::Index: {
        const Type& base = expr.operands.at(0).type;
        node.element_size = node.size;
        node.element_count = base.is_array() ? base.array_size : base.is_matrix() ? base.columns : base.rows;
        protect_operands(node);
        break;
      }
      case ExprKind::Member: {
        const StructType& type = module_.structs.at(expr.operands.at(0).type.struct_index);
        for (int member = 0; member < expr.member; ++member)
          node.member_offset += size_of(type.members.at(member).type);
        break;
      }
      case ExprKind::Operation:
        node.slot = allocate(node.size);
        if (expr.op == Operator::PreIncrement || expr.op == Operator::PreDecrement ||
            expr.op == Operator::PostIncrement || expr.op == Operator::PostDecrement)
          node.has_side_effects = true;
        if (expr.op != Operator::LogicalAnd && expr.op != Operator::LogicalOr) protect_operands(node);
        node.float_scalars = node.operands.size() == 2 && has_float_scalar_form(expr.op) &&
                             expr.operands[0].type == Type{Scalar::Float} &&
                             expr.operands[1].type == Type{Scalar::Float};
        break;
      case ExprKind::Assign:
        node.has_side_effects = true;
        node.slot = allocate(node.size);
        break;
      case ExprKind::Select:
      case ExprKind::Comma:
        break;
      case ExprKind::Construct:
        node.slot = allocate(node.size);
        break;
      case ExprKind::Call: {
        const Function& callee = module_.functions.at(expr.function);
        if (callee.parameters.size() != expr.operands.size())
          contract_broken(fmt::format("a call of '{}' with {} arguments for {} parameters", callee.name,
                                      expr.operands.size(), callee.parameters.size()));
        node.function = expr.function;
        node.has_side_effects = true;
        node.slot = allocate(node.size);
        int arguments_size = 0;
        node.first_place = place_count_;
        for (int parameter : callee.parameters) {
          const Variable& variable = module_.variables.at(parameter);
          arguments_size += size_of(variable.type);
          if (variable.qualifier != ParameterQualifier::In) ++place_count_;
        }
        node.scratch = allocate(arguments_size);
        if (current_function_ >= 0) callees_[current_function_].push_back(expr.function);
        break;
      }
      case ExprKind::BuiltinCall:
        node.slot = allocate(node.size);
        if (expr.builtin == Builtin::Modf) node.has_side_effects = true;
        protect_operands(node);
        break;
    }
    return node;
  }

  Statement compile(const Stmt& stmt) {
    Statement statement;
    statement.kind = stmt.kind;
    statement.location = stmt.location;
    statement.has_value = stmt.has_value;
    statement.has_step = stmt.has_step;
    statement.has_condition = stmt.has_condition;
    statement.test_first = stmt.test_first;
    const bool has_expression =
        stmt.kind == StmtKind::Expression || stmt.kind == StmtKind::If || stmt.kind == StmtKind::Switch ||
        (stmt.kind == StmtKind::Loop && stmt.has_condition) ||
        ((stmt.kind == StmtKind::Declaration || stmt.kind == StmtKind::Return || stmt.kind == StmtKind::Case) &&
         stmt.has_value);
    if (has_expression) statement.expression = compile(stmt.expression);
    if (stmt.kind == StmtKind::Loop && stmt.has_step) statement.step = compile(stmt.step);
    if (stmt.kind == StmtKind::Declaration) {
      statement.variable_offset = variable_offsets_.at(stmt.variable);
      statement.variable_size = size_of(module_.variables[stmt.variable].type);
    }
    if (stmt.kind == StmtKind::Case && stmt.has_value && statement.expression.kind != ExprKind::Constant)
      contract_broken("a case label that is not a constant");
    for (const Stmt& child : stmt.body) statement.body.push_back(compile(child));
    if (stmt.kind == StmtKind::Switch) {
      for (int index = 0; index < static_cast<int>(statement.body.size()); ++index) {
        const Statement& child = statement.body[index];
        if (child.kind == StmtKind::Case && child.has_value)
          statement.cases.emplace_back(child.expression.constant.at(0), index);
        else if (child.kind == StmtKind::Case)
          statement.default_case = index;
        else if (child.kind == StmtKind::Declaration)
          statement.body_variables.emplace_back(child.variable_offset, child.variable_size);
      }
    }
    return statement;
  }

  /// An entry point is called with p as its first parameter: one vec3.
  void check_entry_point(int index) const {
    const Function& function = module_.functions[index];
    if (function.parameters.empty() || module_.variables.at(function.parameters[0]).type.components() != 3)
      contract_broken(fmt::format("the entry point '{}' does not take a vec3", function.name));
  }

  /// The frame gives each function's variables one place, which a recursive call would overwrite.
  void check_no_recursion() const {
    enum class Mark { Unvisited, OnPath, Done };
    std::vector<Mark> marks(module_.functions.size(), Mark::Unvisited);
    auto visit = [&](auto& self, int function) -> void {
      marks[function] = Mark::OnPath;
      for (int callee : callees_[function]) {
        if (marks[callee] == Mark::OnPath) {
          const Function& recursive = module_.functions[callee];
          throw InputError(
              fmt::format("{}:{}:{}: '{}' calls itself, directly or through other functions; GLSL "
                          "forbids recursion",
                          module_.file_name, recursive.location.line, recursive.location.column, recursive.name));
        }
        if (marks[callee] == Mark::Unvisited) self(self, callee);
      }
      marks[function] = Mark::Done;
    };
    for (int function = 0; function < static_cast<int>(marks.size()); ++function)
      if (marks[function] == Mark::Unvisited) visit(visit, function);
  }

  const Module& module_;
  std::vector<int> variable_offsets_;
  int frame_size_ = 0;
  int place_count_ = 0;
  /// The function being compiled (-1 for the globals' initializers), and whom each function calls.
  int current_function_ = -1;
  std::vector<std::vector<int>> callees_;
};

}  // namespace

Program compile_program(const Module& module) { return ProgramCompiler(module).compile(); }

}  // namespace clmarch::glsl::interpreter

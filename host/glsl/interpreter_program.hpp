// The interpreter's compiled form of a Module: the IR's tree again, with every variable and every
// intermediate value given a fixed offset in one frame of doubles, so that an evaluation allocates
// nothing. GLSL forbids recursion, so a function's variables need one place for all of its calls.
#pragma once

#include "glsl/glsl_ir.hpp"

#include <string>
#include <vector>

namespace clmarch::glsl::interpreter {

/// An expression node. Values are flattened to doubles: a vector's components, a matrix's columns
/// in turn, a struct's members and an array's elements in order; ints, uints and bools exactly.
struct Node {
  ExprKind kind = ExprKind::Constant;
  Type type;
  SourceLocation location;
  Operator op = Operator::Add;
  bool compound = false;
  Builtin builtin = Builtin::Abs;
  /// Doubles of the value.
  int size = 0;
  /// Frame offset where the node computes its value, or -1 where it computes none (a variable).
  int slot = -1;
  /// Frame offset of copies: of the earlier operands' values when a later operand has side effects
  /// (Operation, BuiltinCall, Index), or of a Call's arguments before they enter the parameters.
  int scratch = -1;
  /// Whether evaluating the node may write a variable (an assignment, ++, a call, modf).
  bool has_side_effects = false;
  /// Whether the earlier operands' values are copied to scratch before the later ones run.
  bool protects_operands = false;
  /// Operation: one of apply_float_scalars' operators on two float scalars, the common case done
  /// without the general operators' dispatch.
  bool float_scalars = false;
  /// Variable: the variable's frame offset.
  int variable_offset = 0;
  /// Member: the member's offset in the struct.
  int member_offset = 0;
  /// Index: doubles per element and elements of operands[0] (array, vector or matrix columns).
  int element_size = 0;
  int element_count = 0;
  /// Call: index into Program::functions, and of its first out or inout argument's place.
  int function = -1;
  int first_place = 0;
  /// Swizzle: component indices.
  std::vector<int> components;
  /// Constant: the value.
  std::vector<double> constant;
  std::vector<Node> operands;
};

/// A statement, as Stmt with its expressions compiled.
struct Statement {
  StmtKind kind = StmtKind::Block;
  SourceLocation location;
  Node expression;
  bool has_value = false;
  Node step;
  bool has_step = false;
  bool has_condition = true;
  bool test_first = true;
  /// Declaration: the variable's frame offset and size.
  int variable_offset = 0;
  int variable_size = 0;
  std::vector<Statement> body;
  /// Switch: each label's value with the index of its Case in body, and default's index or -1.
  std::vector<std::pair<double, int>> cases;
  int default_case = -1;
  /// Switch: the variables declared directly in its body, zeroed on entry since a case label can
  /// jump over their declaration (frame offset, size).
  std::vector<std::pair<int, int>> body_variables;
};

/// A parameter of a compiled function.
struct Parameter {
  int offset = 0;
  int size = 0;
  ParameterQualifier qualifier = ParameterQualifier::In;
};

/// A user function.
struct CompiledFunction {
  std::string name;
  std::vector<Parameter> parameters;
  /// Doubles of the return value; 0 for void.
  int return_size = 0;
  Statement body;
};

/// A uniform's place in the frame.
struct UniformSlot {
  int offset = 0;
  int size = 0;
  UniformKind kind = UniformKind::None;
};

/// A compiled module.
struct Program {
  std::string file_name;
  std::vector<CompiledFunction> functions;
  /// Module::globals, compiled: Declarations run at the start of each entry point's call.
  std::vector<Statement> globals;
  std::vector<UniformSlot> uniforms;
  /// Doubles of the frame, and places (out and inout arguments) a call of an entry point uses.
  int frame_size = 0;
  int place_count = 0;
  int distance_function = -1;
  int color_function = -1;
};

/// Compiles module. Throws InputError where functions call each other in a cycle (recursion, which
/// GLSL forbids), std::logic_error where the module breaks glsl_ir.hpp's contract.
Program compile_program(const Module& module);

}  // namespace clmarch::glsl::interpreter

// The translation of one function body (or the globals' initialisation) to OpenCL C statements.
// Expressions become C expressions where C keeps GLSL's meaning; where it would not (an operand
// read after a later operand's side effect, out arguments that are not plain variables, a branch
// of && or ?: that needs statements) the emitter hoists work into statements ahead of the one it
// translates, in GLSL's left-to-right order.
#pragma once

#include "glsl/opencl_scope.hpp"

#include <string>
#include <vector>

namespace clmarch::glsl::opencl {

/// What the translation knows of the whole module.
struct ProgramInfo {
  /// Per function: its C name, whether it takes the globals' pointer (it or a callee reads a
  /// global, iTime or iFrame) and whether it may write a global.
  std::vector<std::string> function_names;
  std::vector<bool> needs_globals;
  std::vector<bool> writes_globals;
  /// The C type of the globals' struct, empty when the module has none.
  std::string globals_type;
};

/// Statements ahead of the one being translated, indented relative to it.
using Lines = std::vector<std::string>;

/// Output with #line directives: a line of a user statement names its line in the user's file,
/// a directive written only where the count of lines since the last one does not already say it.
class Writer {
 public:
  explicit Writer(const std::string& file_name);
  /// A line at the current indentation; user_line > 0: of that line of the user's file.
  void line(const std::string& text, int user_line = 0);
  void lines(const Lines& lines, int user_line);
  void indent() { indent_ += 2; }
  void outdent() { indent_ -= 2; }
  const std::string& text() const { return text_; }

 private:
  std::string quoted_file_;
  std::string text_;
  int indent_ = 0;
  /// The user line the next output line has after the last directive; 0 before any.
  int next_line_ = 0;
};

/// An emitted expression.
struct Value {
  std::string text;
  int precedence = kPostfix;
  /// A constant or a temporary: no side effect can change what it reads.
  bool stable = false;
};

/// An lvalue with its index expressions evaluated (so it may be read and written again): a C
/// lvalue `text`, or a vector's component chosen at run time (`vector`[`index`]).
struct LValue {
  std::string text;
  Type type;
  /// The variable at its root.
  int variable = -1;
  /// A component of a vector picked by a dynamic index: text is the vector, index the int.
  bool dynamic_component = false;
  std::string index;
  Type vector_type;
  /// Whether the lvalue is a plain local variable or parameter (not a global): what passes it to
  /// an out parameter by address (&x_, or x_ when it is an out parameter itself).
  bool plain_variable = false;
  std::string address;
  /// Swizzle components applied to text (for composing swizzles of swizzles); empty for none.
  std::vector<int> swizzle;
  std::string swizzle_base;
};

class FunctionEmitter {
 public:
  /// globals: the expression of the globals' pointer here ("globals"), empty where none exists.
  FunctionEmitter(Scope& scope, const ProgramInfo& info, std::string globals);

  /// The C definition of function `index` under its name, with #line from its locations.
  void function(int index, Writer& out);
  /// Statements initialising the globals (Module::globals) through the globals' pointer.
  void global_initialisers(Writer& out);

 private:
  // Statements (opencl_statements.cpp).
  void statement(const Stmt& stmt, Writer& out);
  void block_body(const std::vector<Stmt>& body, Writer& out);
  void loop(const Stmt& stmt, Writer& out);
  void declaration(const Stmt& stmt, Writer& out);
  /// The expression as statements, its value discarded.
  void effect_statements(const Expr& expr, Lines& out);
  std::string local_name(int variable);

  // Expressions (opencl_expressions.cpp).
  Value emit(const Expr& expr, Lines& pre);
  /// Operands evaluated left to right: each one read before a later one's side effects.
  std::vector<Value> in_order(const std::vector<const Expr*>& operands, Lines& pre);
  Value temporary(const Value& value, const Type& type, Lines& pre);
  std::string temporary_name();
  Value variable(const Expr& expr);
  Value swizzle(const Expr& expr, Lines& pre);
  Value index(const Expr& expr, Lines& pre);
  Value operation(const Expr& expr, Lines& pre);
  Value arithmetic(Operator op, const Type& result, const Value& a, const Type& a_type, const Value& b,
                   const Type& b_type);
  Value logical(const Expr& expr, Lines& pre);
  Value select(const Expr& expr, Lines& pre);
  Value assignment(const Expr& expr, Lines& pre, bool discarded);
  Value increment(const Expr& expr, Lines& pre, bool discarded);
  Value construct(const Expr& expr, Lines& pre);
  Value convert(const Value& value, const Type& from, Scalar to);
  Value call(const Expr& expr, Lines& pre);
  /// Arguments of a call, out and inout ones passed by address, through temporaries copied back
  /// after the call unless plain variables; returns the call's value.
  Value call_with_places(const std::string& callee, const std::vector<std::string>& leading,
                         const std::vector<const Expr*>& arguments, const std::vector<ParameterQualifier>& qualifiers,
                         const Type& result, Lines& pre);
  LValue lvalue(const Expr& expr, Lines& pre);
  std::string read(const LValue& place);
  std::string write(const LValue& place, const std::string& value);
  std::string index_text(const Expr& index, Lines& pre);

  // Built-ins (opencl_builtins.cpp).
  Value builtin(const Expr& expr, Lines& pre);

  bool has_effects(const Expr& expr) const;

  Scope& scope_;
  const ProgramInfo& info_;
  std::string globals_;
  std::vector<std::string> local_names_;
  std::vector<bool> out_parameter_;
  std::vector<std::string> used_local_names_;
  int temporaries_ = 0;
};

}  // namespace clmarch::glsl::opencl

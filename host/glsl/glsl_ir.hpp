// The typed program of a user's GLSL distance code, as the front end (glsl_front_end) lowers it from
// glslang's checked tree: overloads resolved, implicit conversions explicit, every operator's
// operand shapes spelled (vector x matrix is its own operation). The OpenCL translation and the
// double-precision interpreter both read this, never glslang's headers.
#pragma once

#include <string>
#include <vector>

namespace clmarch::glsl {

/// Where a construct is in the user's source: the file named in messages, 1-based line and column.
struct SourceLocation {
  int line = 0;
  int column = 0;
};

/// The scalar of a type's components.
enum class Scalar { Void, Bool, Int, Uint, Float };

/// A GLSL type: void, a scalar, a vector (columns 1, rows 2-4), a matrix (columns and rows 2-4,
/// column-major as GLSL), or a struct of Module::structs; any of them may be a one-dimensional array.
struct Type {
  Scalar scalar = Scalar::Void;
  /// Vector size; a matrix's rows; 1 for scalars and structs.
  int rows = 1;
  /// A matrix's columns; 1 otherwise.
  int columns = 1;
  /// Index into Module::structs, or -1.
  int struct_index = -1;
  /// Elements of an array type; 0: not an array.
  int array_size = 0;

  bool is_void() const { return scalar == Scalar::Void && struct_index < 0; }
  bool is_struct() const { return struct_index >= 0; }
  bool is_array() const { return array_size > 0; }
  bool is_matrix() const { return columns > 1; }
  bool is_vector() const { return columns == 1 && rows > 1 && !is_struct(); }
  bool is_scalar() const { return columns == 1 && rows == 1 && !is_struct() && scalar != Scalar::Void; }
  /// Scalar components of one element (rows x columns; 0 for structs).
  int components() const { return is_struct() ? 0 : rows * columns; }
  /// The element type of an array (array_size 0).
  Type element() const {
    Type t = *this;
    t.array_size = 0;
    return t;
  }
  bool operator==(const Type&) const = default;
};

/// A member of a struct type.
struct StructMember {
  std::string name;
  Type type;
};

/// A user's struct type.
struct StructType {
  std::string name;
  std::vector<StructMember> members;
};

/// Values the shader reads as uniforms; their meaning is documented in docs/scene-format.md.
enum class UniformKind {
  None,
  /// iTime: the scene's time t.
  Time,
  /// iResolution: (render.width, render.height, 1).
  Resolution,
  /// iFrame: floor(60 t), Shadertoy's frame at 60 frames a second.
  Frame,
  /// iMouse: (0, 0, 0, 0).
  Mouse,
  /// iTimeDelta: 1/60.
  TimeDelta,
};

/// Where a variable lives.
enum class Storage {
  /// A global of the shader: initialised at the start of every call of an entry point.
  Global,
  /// A global declared const: its initialiser is a constant expression.
  GlobalConst,
  /// A local of a function, zero-initialised where it has no initialiser (as WebGL does).
  Local,
  /// A function parameter (see Variable::qualifier).
  Parameter,
  /// One of the shader's uniforms (UniformKind).
  Uniform,
};

/// How a parameter passes its argument: copied in, copied out on return, or both.
enum class ParameterQualifier { In, Out, InOut };

/// A variable: a global, a local, a parameter or a uniform. Each declaration is its own variable,
/// so shadowing names stay distinct; Module::variables holds them all, referenced by index.
struct Variable {
  std::string name;
  Type type;
  Storage storage = Storage::Local;
  ParameterQualifier qualifier = ParameterQualifier::In;
  UniformKind uniform = UniformKind::None;
  SourceLocation location;
};

/// GLSL's built-in functions that a distance function may call, by their GLSL names. Each takes
/// GLSL's argument shapes (genType, vector-scalar forms), the types on the call say which.
enum class Builtin {
  Radians,
  Degrees,
  Sin,
  Cos,
  Tan,
  Asin,
  Acos,
  Atan /* one argument */,
  Atan2 /* atan(y, x) */,
  Sinh,
  Cosh,
  Tanh,
  Asinh,
  Acosh,
  Atanh,
  Pow,
  Exp,
  Log,
  Exp2,
  Log2,
  Sqrt,
  InverseSqrt,
  Abs,
  Sign,
  Floor,
  Trunc,
  Round,
  RoundEven,
  Ceil,
  Fract,
  Mod,
  Modf,
  Min,
  Max,
  Clamp,
  Mix,
  Step,
  SmoothStep,
  IsNan,
  IsInf,
  FloatBitsToInt,
  FloatBitsToUint,
  IntBitsToFloat,
  UintBitsToFloat,
  Length,
  Distance,
  Dot,
  Cross,
  Normalize,
  FaceForward,
  Reflect,
  Refract,
  MatrixCompMult,
  OuterProduct,
  Transpose,
  Determinant,
  Inverse,
  LessThan,
  LessThanEqual,
  GreaterThan,
  GreaterThanEqual,
  Equal,
  NotEqual,
  Any,
  All,
  Not,
};

/// Operators of GLSL expressions. Arithmetic ones are component-wise over their operands' shapes
/// (a scalar operand applies to every component); the matrix products are their own operators.
enum class Operator {
  // Unary.
  Negate,
  LogicalNot,
  BitwiseNot,
  PreIncrement,
  PreDecrement,
  PostIncrement,
  PostDecrement,
  // Binary, component-wise (Modulo: integers' %).
  Add,
  Subtract,
  Multiply,
  Divide,
  Modulo,
  ShiftLeft,
  ShiftRight,
  BitwiseAnd,
  BitwiseOr,
  BitwiseXor,
  // Linear algebra: matrix x vector, vector x matrix (= transpose(m) x v), matrix x matrix.
  MatrixTimesVector,
  VectorTimesMatrix,
  MatrixTimesMatrix,
  // Comparisons giving one bool: scalars' ordering; == and != of whole values of any type.
  Less,
  Greater,
  LessEqual,
  GreaterEqual,
  Equal,
  NotEqual,
  // Short-circuit logic and ^^.
  LogicalAnd,
  LogicalOr,
  LogicalXor,
};

/// Kinds of expression nodes.
enum class ExprKind {
  /// Constant: `constant` holds its components (a struct's or array's flattened in order).
  Constant,
  /// A variable by index.
  Variable,
  /// operands[0] with the components `components` (.xzy, a swizzle of one or more).
  Swizzle,
  /// operands[0][operands[1]]: an array element, a vector component or a matrix column.
  Index,
  /// operands[0].member of a struct (member: the member's index).
  Member,
  /// op applied to operands (one or two).
  Operation,
  /// operands[0] = operands[1], or operands[0] op= operands[1] with compound set (op the operator).
  Assign,
  /// operands[0] ? operands[1] : operands[2], only the chosen branch evaluated.
  Select,
  /// operands[0], operands[1], ...: each evaluated in turn, the last one's value.
  Comma,
  /// The constructor of `type` from operands, with GLSL's rules (components taken in order; a
  /// matrix from one scalar is diagonal, from a matrix the overlap with identity elsewhere; a
  /// conversion between scalar types when the one operand's scalar differs).
  Construct,
  /// A user function (function: index into Module::functions) with its arguments; out and inout
  /// arguments are lvalues, written back when it returns.
  Call,
  /// A built-in function of its arguments.
  BuiltinCall,
};

/// One expression node; `type` is its GLSL type.
struct Expr {
  ExprKind kind = ExprKind::Constant;
  Type type;
  SourceLocation location;
  std::vector<Expr> operands;
  /// Operation, and compound Assign.
  Operator op = Operator::Add;
  bool compound = false;
  Builtin builtin = Builtin::Abs;
  /// Variable: index into Module::variables.
  int variable = -1;
  /// Call: index into Module::functions.
  int function = -1;
  /// Member: the member's index.
  int member = -1;
  /// Swizzle: component indices, 0-3.
  std::vector<int> components;
  /// Constant: the components in order, ints and bools as exact doubles (bools 0 or 1).
  std::vector<double> constant;
};

/// The variable an lvalue names at its root (q in q.xy[1]), or -1.
inline int root_variable(const Expr& expr) {
  const Expr* e = &expr;
  while (e->kind != ExprKind::Variable && !e->operands.empty()) e = &e->operands[0];
  return e->kind == ExprKind::Variable ? e->variable : -1;
}

/// Kinds of statements.
enum class StmtKind {
  /// expression;
  Expression,
  /// A local's declaration (variable), with initializer when it has one.
  Declaration,
  /// { body... }
  Block,
  /// if (condition) body[0] else body[1] (body size 1 without else).
  If,
  /// A loop: while (condition) body[0] with step after each iteration; condition absent when
  /// has_condition is false, step when has_step is false; test_first false for do-while. A for
  /// loop's init is the statement before it in a Block the front end wraps around both.
  Loop,
  /// switch (condition) { body... }, whose body holds Case statements among the others.
  Switch,
  /// `case constant:` (has_value) or `default:` inside a switch body.
  Case,
  Return,
  Break,
  Continue,
};

/// One statement.
struct Stmt {
  StmtKind kind = StmtKind::Block;
  SourceLocation location;
  /// Expression: the expression; If, Loop, Switch: the condition; Declaration: the initializer
  /// (when has_value); Return: the value (when has_value); Case: the label's constant.
  Expr expression;
  bool has_value = false;
  /// Loop: the step expression, evaluated after each iteration (when has_step).
  Expr step;
  bool has_step = false;
  bool has_condition = true;
  bool test_first = true;
  /// Declaration: index into Module::variables.
  int variable = -1;
  /// Block and Switch: the statements; If: then, else; Loop: the body.
  std::vector<Stmt> body;
};

/// A user function: its GLSL name (overloads share it), parameters (Variable indices in order),
/// return type and body.
struct Function {
  std::string name;
  Type return_type;
  std::vector<int> parameters;
  Stmt body;
  SourceLocation location;
};

/// The user's program: what the entry points reach, in an order where a function's callees and
/// a global's initializer come before it.
struct Module {
  /// The file messages and #line name ("shapes.glsl", or the scene file for inline code).
  std::string file_name;
  std::vector<StructType> structs;
  std::vector<Variable> variables;
  /// Globals (Storage::Global or GlobalConst) with their initializers, in declaration order: the
  /// statements are Declarations.
  std::vector<Stmt> globals;
  std::vector<Function> functions;
  /// The distance function: takes vec3, returns float or vec2/vec3/vec4 whose .x is the distance.
  int distance_function = -1;
  /// The colour function vec3 f(vec3), or -1.
  int color_function = -1;
};

}  // namespace clmarch::glsl

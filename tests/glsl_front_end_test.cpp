// The GLSL front end: glslang's diagnostics with the user's file, line and column; what a distance
// function cannot use, refused by name; and the typed IR it lowers to (the operators that string
// rewriting gets wrong: vector x matrix, swizzle inout arguments).
#include "common/errors.hpp"
#include "glsl/glsl_front_end.hpp"

#include <gtest/gtest.h>

#include <string>

namespace clmarch::glsl {
namespace {

Module compile_code(const std::string& code, int first_line = 1) {
  Source source;
  source.code = code;
  source.file_name = "shapes.glsl";
  source.first_line = first_line;
  return compile(source);
}

/// The InputError's message compiling code, or "no error".
std::string front_end_error(const std::string& code, int first_line = 1) {
  try {
    compile_code(code, first_line);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

const Function& function_named(const Module& module, const std::string& name) {
  for (const Function& function : module.functions) {
    if (function.name == name) return function;
  }
  throw std::logic_error("no function " + name);
}

/// The expression of the first statement of kind Expression in a function's body, depth first.
const Expr* first_expression(const Stmt& statement) {
  if (statement.kind == StmtKind::Expression) return &statement.expression;
  for (const Stmt& inner : statement.body) {
    if (const Expr* found = first_expression(inner)) return found;
  }
  return nullptr;
}

TEST(GlslFrontEnd, GlslangErrorsNameTheFileLineAndColumn) {
  EXPECT_EQ(front_end_error("float map(vec3 p) {\n  return foo(p);\n}\n"),
            "shapes.glsl:2:10: 'foo' : no matching overloaded function found");
  // Inline code in a scene file: lines count from the scene file's line of its first line.
  EXPECT_EQ(front_end_error("float map(vec3 p) {\n  return foo(p);\n}\n", 12),
            "shapes.glsl:13:10: 'foo' : no matching overloaded function found");
  EXPECT_EQ(front_end_error("float map(vec3 p) { return length(p) - 1.0 }"),
            "shapes.glsl:1: syntax error, unexpected RIGHT_BRACE, expecting COMMA or SEMICOLON");
}

TEST(GlslFrontEnd, WhatADistanceFunctionCannotUseIsRefusedByName) {
  EXPECT_EQ(front_end_error("float map(vec3 p) {\n  return texture(iChannel0, p.xy).x;\n}\n"),
            "shapes.glsl:2:10: texture lookups cannot be used in a distance function: it has no texture units");
  EXPECT_EQ(front_end_error("float map(vec3 p) { return dFdx(p.x); }"),
            "shapes.glsl:1:28: 'dFdx': derivatives cannot be used in a distance function (it is evaluated at points, "
            "not over a pixel's neighbours)");
  EXPECT_NE(front_end_error("float map(vec3 p) { return fwidth(p.x); }").find("'fwidth': derivatives"),
            std::string::npos);
  EXPECT_EQ(front_end_error("float map(vec3 p) { if (p.x > 0.0) discard; return 1.0; }"),
            "shapes.glsl:1:36: 'discard' cannot be used in a distance function: it has no fragment to discard");
  EXPECT_NE(front_end_error("float map(vec3 p) { return gl_FragCoord.x; }").find("'gl_FragCoord' has no meaning"),
            std::string::npos);
  EXPECT_EQ(front_end_error("uniform float speed;\nfloat map(vec3 p) { return speed; }"),
            "shapes.glsl:2:28: uniform 'speed': only iTime, iResolution, iFrame, iMouse and iTimeDelta are provided "
            "(use a const or a #define, or the scene's `defines:`)");
  EXPECT_EQ(front_end_error("#version 300 es\nfloat map(vec3 p) { return 1.0; }"),
            "shapes.glsl:1: remove #version: clmarch reads the code as GLSL ES 3.00 (#version 300 es), as WebGL 2 "
            "and Shadertoy do");
}

TEST(GlslFrontEnd, TheEntryPointMustExistWithItsSignature) {
  EXPECT_EQ(front_end_error("float sdf(vec3 p) { return 1.0; }"),
            "shapes.glsl: no function float, vec2, vec3 or vec4 map(vec3)");
  EXPECT_EQ(front_end_error("float map(vec3 p, float t) { return 1.0; }"),
            "shapes.glsl: no function float, vec2, vec3 or vec4 map(vec3) (the ones named 'map' take other "
            "parameters)");
  EXPECT_EQ(front_end_error("int map(vec3 p) { return 1; }"),
            "shapes.glsl:1:5: 'map' returns int; clmarch needs float, vec2, vec3 or vec4 map(vec3)");
  EXPECT_EQ(front_end_error("float f(float x);\nfloat map(vec3 p) { return f(p.x); }"),
            "shapes.glsl:2:28: 'f' is declared but never defined");
  Source source;
  source.code = "float map(vec3 p) { return 1.0; } float albedo(vec3 p) { return 1.0; }";
  source.file_name = "shapes.glsl";
  source.color_function = "albedo";
  try {
    compile(source);
    ADD_FAILURE() << "a colour function returning float was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "shapes.glsl:1:41: 'albedo' returns float; clmarch needs vec3 albedo(vec3)");
  }
}

TEST(GlslFrontEnd, VectorTimesMatrixAndMatrixTimesVectorStayApart) {
  const Module module = compile_code(
      "mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }\n"
      "float map(vec3 p) {\n"
      "  p.xz *= rot(iTime);\n"
      "  vec2 q = rot(0.5) * p.xy;\n"
      "  vec2 r = p.xy * rot(0.5);\n"
      "  return q.x + r.y;\n"
      "}\n");
  const Function& map = function_named(module, "map");
  const Expr* rotate = first_expression(map.body);
  ASSERT_NE(rotate, nullptr);
  EXPECT_EQ(rotate->kind, ExprKind::Assign);
  EXPECT_TRUE(rotate->compound);
  EXPECT_EQ(rotate->op, Operator::VectorTimesMatrix);
  ASSERT_EQ(rotate->operands[0].kind, ExprKind::Swizzle);
  EXPECT_EQ(rotate->operands[0].components, (std::vector<int>{0, 2}));
  EXPECT_EQ(rotate->operands[1].kind, ExprKind::Call);
  EXPECT_EQ(module.variables[rotate->operands[1].operands[0].variable].uniform, UniformKind::Time);
  // The two products, in the assignments' right-hand sides.
  std::vector<Operator> products;
  std::function<void(const Stmt&)> walk = [&](const Stmt& statement) {
    if (statement.kind == StmtKind::Expression && statement.expression.kind == ExprKind::Assign &&
        statement.expression.operands[1].kind == ExprKind::Operation) {
      products.push_back(statement.expression.operands[1].op);
    }
    for (const Stmt& inner : statement.body) walk(inner);
  };
  walk(map.body);
  EXPECT_EQ(products, (std::vector<Operator>{Operator::MatrixTimesVector, Operator::VectorTimesMatrix}));
}

TEST(GlslFrontEnd, SwizzleInoutArgumentsKeepTheirQualifierAndLvalue) {
  const Module module = compile_code(
      "void pR(inout vec2 p, float a) { p = cos(a) * p + sin(a) * vec2(p.y, -p.x); }\n"
      "void split(vec3 p, out float x, out float rest) { x = p.x; rest = p.y + p.z; }\n"
      "float map(vec3 p) { pR(p.xz, 0.3); float a, b; split(p, a, b); return a + b; }\n");
  const Function& rotate = function_named(module, "pR");
  ASSERT_EQ(rotate.parameters.size(), 2u);
  EXPECT_EQ(module.variables[rotate.parameters[0]].qualifier, ParameterQualifier::InOut);
  EXPECT_EQ(module.variables[rotate.parameters[1]].qualifier, ParameterQualifier::In);
  const Function& split = function_named(module, "split");
  EXPECT_EQ(module.variables[split.parameters[1]].qualifier, ParameterQualifier::Out);
  const Expr* call = first_expression(function_named(module, "map").body);
  ASSERT_NE(call, nullptr);
  ASSERT_EQ(call->kind, ExprKind::Call);
  EXPECT_EQ(module.functions[call->function].name, "pR");
  ASSERT_EQ(call->operands[0].kind, ExprKind::Swizzle);
  EXPECT_EQ(call->operands[0].components, (std::vector<int>{0, 2}));
}

TEST(GlslFrontEnd, CalleesComeBeforeCallersAndUncalledFunctionsAreLeftOut) {
  const Module module = compile_code(
      "float unused(float x) { return x; }\n"
      "float b(float x) { return x * 2.0; }\n"
      "float a(float x) { return b(x) + 1.0; }\n"
      "float map(vec3 p) { return a(p.x) + b(p.y); }\n");
  std::vector<std::string> names;
  for (const Function& function : module.functions) names.push_back(function.name);
  EXPECT_EQ(names, (std::vector<std::string>{"b", "a", "map"}));
  EXPECT_EQ(module.functions[module.distance_function].name, "map");
  EXPECT_EQ(module.color_function, -1);
}

TEST(GlslFrontEnd, OverloadsAreDistinctFunctions) {
  const Module module = compile_code(
      "float len(vec2 p) { return length(p); }\n"
      "float len(vec3 p) { return length(p); }\n"
      "float map(vec3 p) { return len(p) + len(p.xy); }\n");
  int overloads = 0;
  for (const Function& function : module.functions) overloads += function.name == "len";
  EXPECT_EQ(overloads, 2);
}

TEST(GlslFrontEnd, BuiltinsKeepTheirGlslMeaning) {
  const Module module = compile_code("float map(vec3 p) { return atan(p.y, p.x) + atan(p.z) + mod(p.x, 2.0); }\n");
  std::vector<Builtin> builtins;
  std::function<void(const Expr&)> walk = [&](const Expr& expr) {
    if (expr.kind == ExprKind::BuiltinCall) builtins.push_back(expr.builtin);
    for (const Expr& operand : expr.operands) walk(operand);
  };
  for (const Stmt& statement : function_named(module, "map").body.body) {
    std::function<void(const Stmt&)> statements = [&](const Stmt& s) {
      if (s.kind == StmtKind::Return) walk(s.expression);
      for (const Stmt& inner : s.body) statements(inner);
    };
    statements(statement);
  }
  EXPECT_EQ(builtins, (std::vector<Builtin>{Builtin::Atan2, Builtin::Atan, Builtin::Mod}));
}

// glslang keeps no node for `float z;`: its declaration is found in the text, so that WebGL's
// zeroing at the declaration happens where the user wrote it (each iteration, in a loop body).
TEST(GlslFrontEnd, LocalsAreDeclaredWhereTheSourceDeclaresThem) {
  const Module module = compile_code(
      "float map(vec3 p) {\n"
      "  float total;\n"
      "  for (int i = 0; i < 3; i++) {\n"
      "    float z;\n"
      "    z += 1.0;\n"
      "    total += z;\n"
      "  }\n"
      "  return total;\n"
      "}\n");
  const Stmt& body = function_named(module, "map").body;
  // The depth of each declaration: total's in the function's block, z's in the loop's body.
  int total_depth = -1, z_depth = -1;
  std::function<void(const Stmt&, int)> depths = [&](const Stmt& block, int depth) {
    for (const Stmt& statement : block.body) {
      if (statement.kind == StmtKind::Declaration) {
        const std::string& name = module.variables[statement.variable].name;
        if (name == "total") total_depth = depth;
        if (name == "z") z_depth = depth;
      }
      depths(statement, depth + 1);
    }
  };
  depths(body, 0);
  ASSERT_GE(total_depth, 0);
  EXPECT_LT(total_depth, z_depth) << "z is declared inside the loop's body, total outside the loop";
  // Each declared once.
  int declarations = 0;
  std::function<void(const Stmt&)> count = [&](const Stmt& block) {
    for (const Stmt& statement : block.body) {
      declarations += statement.kind == StmtKind::Declaration;
      count(statement);
    }
  };
  count(body);
  EXPECT_EQ(declarations, 3);
}

TEST(GlslFrontEnd, ADeclarationTheTextDoesNotShowGoesToTheTop) {
  const Module module = compile_code(
      "#define DECLARE(name) float name\n"
      "float map(vec3 p) { DECLARE(d); d = length(p); return d - 1.0; }\n");
  const Stmt& body = function_named(module, "map").body;
  ASSERT_FALSE(body.body.empty());
  EXPECT_EQ(body.body.front().kind, StmtKind::Declaration);
}

TEST(GlslFrontEnd, GlobalsKeepTheirInitializersAndDefinesApply) {
  Source source;
  source.code =
      "float scale = 2.0;\n"
      "float material;\n"
      "#if ITER > 2\n"
      "float map(vec3 p) { material = 1.0; return length(p) * scale - float(ITER); }\n"
      "#endif\n";
  source.file_name = "shapes.glsl";
  source.defines = {{"ITER", "4"}};
  const Module module = compile(source);
  ASSERT_EQ(module.globals.size(), 2u);
  EXPECT_EQ(module.variables[module.globals[0].variable].name, "scale");
  ASSERT_TRUE(module.globals[0].has_value);
  EXPECT_EQ(module.globals[0].expression.constant, (std::vector<double>{2.0}));
  EXPECT_EQ(module.variables[module.globals[1].variable].name, "material");
  EXPECT_FALSE(module.globals[1].has_value);
  source.defines = {{"ITER", "1"}};
  try {
    compile(source);
    ADD_FAILURE() << "the #if did not remove map";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "shapes.glsl: no function float, vec2, vec3 or vec4 map(vec3)");
  }
}

// Shadertoy's `float t = iTime;` (WebGL accepts it; GLSL ES 3.00 needs an extension we enable).
TEST(GlslFrontEnd, GlobalsMayBeInitialisedFromUniforms) {
  const Module module = compile_code(
      "float radius = 0.5 * sin(iTime) + 1.0;\n"
      "vec2 map(vec3 p) { return vec2(length(p) - radius, 1.0); }\n");
  ASSERT_EQ(module.globals.size(), 1u);
  ASSERT_TRUE(module.globals[0].has_value);
  EXPECT_EQ(module.globals[0].expression.kind, ExprKind::Operation);
  EXPECT_EQ(module.functions[module.distance_function].return_type.rows, 2);
}

TEST(GlslFrontEnd, CommasInForStepsAreExpressions) {
  const Module module = compile_code(
      "float map(vec3 p) { float s = 0.0; for (int k = 0, n = 0; k < 3; k++, n += 10) s += float(n); return s; }\n");
  bool found = false;
  std::function<void(const Stmt&)> walk = [&](const Stmt& statement) {
    if (statement.kind == StmtKind::Loop && statement.has_step && statement.step.kind == ExprKind::Comma) found = true;
    for (const Stmt& inner : statement.body) walk(inner);
  };
  walk(function_named(module, "map").body);
  EXPECT_TRUE(found);
}

TEST(GlslFrontEnd, StructsAreLoweredWithTheirMembers) {
  const Module module = compile_code(
      "struct Hit { float d; vec3 color; };\n"
      "Hit closest(Hit a, Hit b) { return a.d < b.d ? a : b; }\n"
      "float map(vec3 p) { Hit h = closest(Hit(length(p) - 1.0, vec3(1)), Hit(p.y, vec3(0))); return h.d; }\n");
  ASSERT_EQ(module.structs.size(), 1u);
  EXPECT_EQ(module.structs[0].name, "Hit");
  ASSERT_EQ(module.structs[0].members.size(), 2u);
  EXPECT_EQ(module.structs[0].members[1].name, "color");
  EXPECT_EQ(module.structs[0].members[1].type.rows, 3);
}

}  // namespace
}  // namespace clmarch::glsl

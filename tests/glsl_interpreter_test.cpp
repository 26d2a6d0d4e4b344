// The GLSL interpreter against closed forms computed here in C++ (and glm, column-major as GLSL):
// every expression and statement kind, the operators, constructors and built-ins, the integers'
// wrapping, the copies of values, out and inout arguments, and what one call keeps to itself.
#include "common/errors.hpp"
#include "glsl/glsl_front_end.hpp"
#include "glsl/glsl_interpreter.hpp"

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include <bit>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace clmarch::glsl {
namespace {

/// Both sides compute in double, at most in another order (glm's inverse against the adjugate):
/// a few ulps of values of order 1 to 100.
constexpr double kTolerance = 1e-12;

Interpreter interpreter_of(const std::string& code, const std::string& color_function = "") {
  Source source;
  source.code = code;
  source.file_name = "test.glsl";
  source.color_function = color_function;
  return Interpreter(compile(source), UniformValues{});
}

double distance_of(const std::string& code, glm::dvec3 p = {}, double time = 0.0) {
  return interpreter_of(code).distance(p, time);
}

/// The colour function `vec3 f(vec3 p)` of code (which needs no map of its own) at p.
glm::dvec3 vec3_of(const std::string& code, glm::dvec3 p = {}, double time = 0.0) {
  return interpreter_of(code + "\nfloat map(vec3 p) { return 0.0; }\n", "f").color(p, time);
}

void expect_near(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = kTolerance) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

double box_distance(glm::dvec3 p, glm::dvec3 size) {
  const glm::dvec3 q = glm::abs(p) - size;
  return glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}

const std::string kBox = R"(
float sdBox(vec3 p, vec3 b) {
  vec3 q = abs(p) - b;
  return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}
)";

TEST(GlslInterpreter, RotatedBoxIsTheBoxAtTheRotatedPoint) {
  const Interpreter interpreter = interpreter_of(kBox + R"(
float map(vec3 p) {
  float c = cos(iTime), s = sin(iTime);
  p.xz *= mat2(c, s, -s, c);
  return sdBox(p, vec3(1.0, 0.5, 0.25));
})");
  for (const glm::dvec3 p : {glm::dvec3(0.0), glm::dvec3(2.0, 0.25, -1.5), glm::dvec3(-0.5, 3.0, 0.75)}) {
    // v * m is (dot(v, column 0), dot(v, column 1)).
    const double c = std::cos(0.75), s = std::sin(0.75);
    const glm::dvec3 rotated(p.x * c + p.z * s, p.y, -p.x * s + p.z * c);
    EXPECT_NEAR(interpreter.distance(p, 0.75), box_distance(rotated, {1.0, 0.5, 0.25}), kTolerance);
  }
}

TEST(GlslInterpreter, SmoothUnionInALoopMatchesItsClosedForm) {
  const Interpreter interpreter = interpreter_of(kBox + R"(
float smin(float a, float b, float k) {
  float h = clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return mix(b, a, h) - k * h * (1.0 - h);
}
float map(vec3 p) {
  float d = length(p) - 1.0;
  for (int i = 0; i < 4; i++) {
    float a = float(i) * 0.5;
    vec3 q = p - vec3(float(i), 0.0, 0.0);
    q.xy = mat2(cos(a), sin(a), -sin(a), cos(a)) * q.xy;
    d = smin(d, sdBox(q, vec3(0.5)), 0.25);
  }
  return d;
})");
  const glm::dvec3 p(1.25, -0.5, 0.75);
  double d = glm::length(p) - 1.0;
  for (int i = 0; i < 4; ++i) {
    const double a = i * 0.5;
    glm::dvec3 q = p - glm::dvec3(i, 0.0, 0.0);
    q = glm::dvec3(std::cos(a) * q.x - std::sin(a) * q.y, std::sin(a) * q.x + std::cos(a) * q.y, q.z);
    const double b = box_distance(q, glm::dvec3(0.5));
    const double h = std::clamp(0.5 + 0.5 * (b - d) / 0.25, 0.0, 1.0);
    d = b * (1.0 - h) + d * h - 0.25 * h * (1.0 - h);
  }
  EXPECT_NEAR(interpreter.distance(p, 0.0), d, kTolerance);
}

TEST(GlslInterpreter, TheDistanceIsTheResultsX) {
  EXPECT_EQ(distance_of("vec2 map(vec3 p) { return vec2(p.y, 7.0); }", {0.0, 1.5, 0.0}), 1.5);
  EXPECT_EQ(distance_of("vec4 map(vec3 p) { return vec4(p.zyx, 7.0); }", {0.0, 0.0, -2.5}), -2.5);
}

TEST(GlslInterpreter, ColorIsTheColourFunctionsVec3) {
  const Interpreter interpreter = interpreter_of(
      "float map(vec3 p) { return length(p) - 1.0; }\nvec3 albedo(vec3 p) { return abs(p) * iTime; }", "albedo");
  expect_near(interpreter.color({-1.0, 2.0, -0.5}, 2.0), {2.0, 4.0, 1.0});
  EXPECT_THROW(interpreter_of("float map(vec3 p) { return 0.0; }").color({}, 0.0), std::logic_error);
}

TEST(GlslInterpreter, ModAndFractFollowFloorForNegatives) {
  for (const double x : {-2.75, -0.5, 0.0, 1.25, 7.5}) {
    expect_near(vec3_of("vec3 f(vec3 p) { return vec3(mod(p.x, 2.0), fract(p.x), mod(p, vec3(-1.5)).x); }", {x, 0, 0}),
                {x - 2.0 * std::floor(x / 2.0), x - std::floor(x), x + 1.5 * std::floor(x / -1.5)});
  }
  expect_near(vec3_of("vec3 f(vec3 p) { return mod(p, 2.0); }", {-2.75, 3.5, -0.25}), {1.25, 1.5, 1.75});
}

TEST(GlslInterpreter, SwizzleInoutArgumentIsWrittenBack) {
  const std::string code = R"(
void pR(inout vec2 p, float a) { p = cos(a) * p + sin(a) * vec2(p.y, -p.x); }
vec3 f(vec3 p) { pR(p.xz, 0.5); return p; })";
  const glm::dvec3 p(1.0, 2.0, 3.0);
  const double c = std::cos(0.5), s = std::sin(0.5);
  expect_near(vec3_of(code, p), {c * p.x + s * p.z, p.y, c * p.z - s * p.x});
}

TEST(GlslInterpreter, ArgumentsAreCopiedInAndOutInOrder) {
  // Copy-in, copy-out: the global g is the copy-out's 5, not the 6 the body gave g itself.
  expect_near(vec3_of(R"(
float g = 1.0;
void h(inout float a) { a = 5.0; g = a + g; }
void both(out float a, out float b) { a = 1.0; b = 2.0; }
vec3 f(vec3 p) {
  h(g);
  float x;
  both(x, x);
  vec3 v = vec3(0.0);
  both(v[int(p.x)], v.z);
  return vec3(g, x, v.x + 10.0 * v.z);
})"),
              {5.0, 2.0, 21.0});
}

TEST(GlslInterpreter, IntegersWrapAtThirtyTwoBits) {
  // Values from p, so that glslang's constant folding does not do the interpreter's work.
  const glm::dvec3 one(1.0, 0.0, 0.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { int i = int(p.x) + 2147483646; i = i + 1; return float(i); }", one),
            -2147483648.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { int i = int(p.x) + 2147483646; i += 2; return float(i); }", one),
            -2147483647.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { int i = 46341 * int(p.x); return float(i * 46341); }", one),
            static_cast<double>(static_cast<std::int32_t>(46341u * 46341u)));
  EXPECT_EQ(distance_of("float map(vec3 p) { int i = -2147483647 - int(p.x); return float(-i); }", one), -2147483648.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { uint u = uint(p.y); u -= 1u; return float(u); }", one), 4294967295.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { uint u = uint(p.x) * 65536u; return float(u * 65536u); }", one), 0.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { int i = 2147483647 * int(p.x); return float(++i); }", one), -2147483648.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { int i = int(p.x) - 2147483647 - 2; return float(abs(i)); }", one),
            -2147483648.0);
}

TEST(GlslInterpreter, IntegerDivisionAndShiftsHaveDefinedResults) {
  const auto at = [](const std::string& expression, glm::dvec3 p) {
    return distance_of(
        "float map(vec3 p) { int a = int(p.x), b = int(p.y); uint u = uint(p.z); return float(" + expression + "); }",
        p);
  };
  EXPECT_EQ(at("a / b", {7, -2, 0}), -3.0);
  EXPECT_EQ(at("a % b", {7, 3, 0}), 1.0);
  EXPECT_EQ(at("a / b", {7, 0, 0}), 0.0);  // Division by zero gives 0.
  EXPECT_EQ(at("a % b", {7, 0, 0}), 0.0);
  EXPECT_EQ(at("u / uint(b)", {0, 0, 7}), 0.0);
  EXPECT_EQ(at("(a - 2147483647 - 2) / b", {1, -1, 0}), -2147483648.0);  // INT_MIN / -1 wraps.
  EXPECT_EQ(at("a << b", {1, 33, 0}), 2.0);                              // Counts are taken modulo 32.
  EXPECT_EQ(at("a >> b", {-16, 2, 0}), -4.0);                            // Arithmetic for int.
  EXPECT_EQ(at("u >> uint(b)", {0, 28, 4294967280.0}), 15.0);            // Logical for uint.
  EXPECT_EQ(at("a << b", {1, 31, 0}), -2147483648.0);
  EXPECT_EQ(at("(a & b) + (a | b) * 100 + (a ^ b) * 10000", {12, 10, 0}), 8.0 + 1400.0 + 60000.0);
  EXPECT_EQ(at("~a", {5, 0, 0}), -6.0);
  EXPECT_EQ(at("~u", {0, 0, 5}), 4294967290.0);
}

TEST(GlslInterpreter, ConversionsFollowTheConstructors) {
  expect_near(vec3_of("vec3 f(vec3 p) { return vec3(ivec3(p)); }", {-1.75, 2.9, 0.5}), {-1.0, 2.0, 0.0});
  expect_near(vec3_of("vec3 f(vec3 p) { return vec3(bvec3(p)); }", {-1.75, 0.0, 0.5}), {1.0, 0.0, 1.0});
  expect_near(vec3_of("vec3 f(vec3 p) { int i = int(p.x); return vec3(float(uint(i)), float(int(p.y > 0.0)), "
                      "float(uint(p.z))); }",
                      {-1.0, 2.0, 3.75}),
              {4294967295.0, 1.0, 3.0});
}

TEST(GlslInterpreter, ConstructorsTakeComponentsInOrder) {
  expect_near(vec3_of("vec3 f(vec3 p) { vec4 v = vec4(p.xy, vec2(p.z, 4.0)); return v.yzw; }", {1, 2, 3}),
              {2.0, 3.0, 4.0});
  expect_near(vec3_of("vec3 f(vec3 p) { return vec3(vec2(p.z), 5.0); }", {1, 2, 3}), {3.0, 3.0, 5.0});
  expect_near(vec3_of("vec3 f(vec3 p) { return vec3(vec4(p, 9.0)); }", {1, 2, 3}), {1.0, 2.0, 3.0});
  // mat2(vec3, float): the components fill column 0, then column 1.
  expect_near(vec3_of("vec3 f(vec3 p) { mat2 m = mat2(p, 4.0); return vec3(m[0][1], m[1][0], m[1][1]); }", {1, 2, 3}),
              {2.0, 3.0, 4.0});
}

TEST(GlslInterpreter, MatrixConstructorsFromOneValue) {
  // From a scalar: the diagonal. From a matrix: its top-left, the identity's elsewhere.
  expect_near(vec3_of("vec3 f(vec3 p) { mat3 m = mat3(p.x); return vec3(m[0][0], m[1][0], m[2][2]); }", {2, 0, 0}),
              {2.0, 0.0, 2.0});
  expect_near(vec3_of(R"(vec3 f(vec3 p) {
  mat3 m = mat3(mat2(p.x, 2.0, 3.0, 4.0));
  return vec3(m[1][1] + 10.0 * m[0][0], m[2][2] + 10.0 * m[2][0], m[0][2]); })",
                      {5, 0, 0}),
              {54.0, 1.0, 0.0});
  expect_near(vec3_of(R"(vec3 f(vec3 p) {
  mat2 m = mat2(mat3(p.x, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0));
  return vec3(m[0][0] + m[0][1], m[1][0], m[1][1]); })",
                      {1, 0, 0}),
              {3.0, 4.0, 5.0});
  expect_near(
      vec3_of("vec3 f(vec3 p) { mat4 m = mat4(mat3(p.x)); return vec3(m[0][0], m[3][3], m[3][0]); }", {2, 0, 0}),
      {2.0, 1.0, 0.0});
}

TEST(GlslInterpreter, MatrixProductsAreGlslsAndGlms) {
  const std::string matrix = "mat3 m = mat3(p.x, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0);";
  const glm::dvec3 p(1.5, -2.0, 0.25);
  const glm::dmat3 m(p.x, 2, 3, 4, 5, 6, 7, 8, 10);
  const glm::dmat3 n(1, 0.5, 0, -1, 2, 0.25, 0, 0, 3);
  const std::string n_glsl = "mat3 n = mat3(1.0, 0.5, 0.0, -1.0, 2.0, 0.25, 0.0, 0.0, 3.0);";
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + " return m * p; }", p), m * p);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + " return p * m; }", p), p * m);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + " vec3 v = p; v *= m; return v; }", p), p * m);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + n_glsl + " return (m * n)[1] + (m * 2.0)[2]; }", p),
              (m * n)[1] + (m * 2.0)[2]);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + n_glsl + " m *= n; return m[2]; }", p), (m * n)[2]);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + " return inverse(m)[1]; }", p), glm::inverse(m)[1]);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + " return transpose(m)[0]; }", p), glm::transpose(m)[0]);
  expect_near(vec3_of("vec3 f(vec3 p) { " + matrix + n_glsl + " return matrixCompMult(m, n)[1]; }", p),
              glm::matrixCompMult(m, n)[1]);
  expect_near(vec3_of("vec3 f(vec3 p) { return outerProduct(p, vec3(1.0, 2.0, 3.0))[2]; }", p),
              glm::outerProduct(p, glm::dvec3(1, 2, 3))[2]);
  EXPECT_NEAR(vec3_of("vec3 f(vec3 p) { " + matrix + " return vec3(determinant(m)); }", p).x, glm::determinant(m),
              kTolerance);
  const glm::dmat4 big(p.x, 2, 3, 4, 0, 1, 0.5, 0, 2, 0, 1, 0.25, 1, 1, 1, 3);
  const std::string big_glsl = "mat4 b = mat4(p.x, 2, 3, 4, 0, 1, 0.5, 0, 2, 0, 1, 0.25, 1, 1, 1, 3);";
  EXPECT_NEAR(vec3_of("vec3 f(vec3 p) { " + big_glsl + " return vec3(determinant(b)); }", p).x, glm::determinant(big),
              kTolerance);
  expect_near(vec3_of("vec3 f(vec3 p) { " + big_glsl + " return inverse(b)[2].xyz; }", p),
              glm::dvec3(glm::inverse(big)[2]));
  const glm::dmat2 small(p.x, 2, 3, 5);
  expect_near(vec3_of("vec3 f(vec3 p) { mat2 s = mat2(p.x, 2, 3, 5); return vec3(inverse(s)[1], determinant(s)); }", p),
              {glm::inverse(small)[1][0], glm::inverse(small)[1][1], glm::determinant(small)});
}

TEST(GlslInterpreter, IndexedAndSwizzledLvalues) {
  expect_near(vec3_of(R"(vec3 f(vec3 p) {
  vec3 a[2];
  a[int(p.x)].y = 5.0;
  a[1].zx = vec2(7.0, 3.0);
  mat3 m = mat3(0.0);
  m[1][2] = 4.0;
  m[2].yx = vec2(1.0, 2.0);
  vec3 v = p;
  v.zy.x = 9.0;
  v.yx = v.xy;
  return vec3(a[0].y + a[1].x + a[1].z * 10.0, m[1].z + m[2].x * 10.0 + m[2].y * 100.0, v.x + v.y * 10.0 + v.z * 100.0);
})",
                      {0.0, 2.0, 3.0}),
              {5.0 + 3.0 + 70.0, 4.0 + 20.0 + 100.0, 2.0 + 0.0 + 900.0});
}

TEST(GlslInterpreter, StructsAndArraysAreCopiedByValue) {
  expect_near(vec3_of(R"(
struct S { vec2 a; float b[2]; };
float change(S s) { s.a.x = 100.0; return s.a.x; }
vec3 f(vec3 p) {
  S s = S(vec2(p.x, 2.0), float[2](3.0, 4.0));
  S t = s;
  t.a.x = 10.0;
  t.b[1] = 20.0;
  float arr[3] = float[3](1.0, 2.0, 3.0);
  float c[3] = arr;
  c[0] = 9.0;
  float changed = change(s);
  return vec3(s.a.x + s.b[1] + changed, t.a.x + t.b[1], arr[0] + c[0]);
})",
                      {1.0, 0.0, 0.0}),
              {105.0, 30.0, 10.0});
}

TEST(GlslInterpreter, EqualityComparesWholeValues) {
  expect_near(vec3_of(R"(
struct S { float x; vec2 v; };
vec3 f(vec3 p) {
  S a = S(1.0, vec2(2.0, p.x));
  S b = a;
  float same = float(a == b);
  b.v.y = 5.0;
  float arrays = float(float[2](p.x, 1.0) == float[2](2.0, 1.0));
  return vec3(same + 10.0 * float(a != b), arrays, float(p.xy != vec2(2.0, 0.0)));
})",
                      {2.0, 0.0, 0.0}),
              {11.0, 1.0, 0.0});
}

TEST(GlslInterpreter, SelectAndLogicEvaluateOnlyWhatTheyNeed) {
  const std::string code = R"(
vec3 f(vec3 p) {
  float x = 0.0;
  float r = p.x > 0.0 ? (x += 1.0) : (x -= 1.0);
  int n = 0;
  bool o = p.x > 0.0 || (n++ > 0);
  bool a = p.x > 0.0 && (n++ > 0);
  return vec3(x + 10.0 * r, float(n), float(o) + 10.0 * float(a) + 100.0 * float((p.x > 0.0) ^^ (p.y > 0.0)));
})";
  expect_near(vec3_of(code, {1.0, 1.0, 0.0}), {11.0, 1.0, 1.0});
  expect_near(vec3_of(code, {-1.0, 1.0, 0.0}), {-11.0, 1.0, 100.0});
}

TEST(GlslInterpreter, IncrementsGiveTheNewOrTheOldValue) {
  expect_near(vec3_of(R"(vec3 f(vec3 p) {
  int i = int(p.x);
  int a = i++;
  int b = ++i;
  vec2 v = vec2(p.y);
  v--;
  mat2 m = mat2(p.z);
  return vec3(float(a) + 10.0 * float(b) + 100.0 * float(i), v.x + v.y, (m++)[0][0] + 10.0 * m[1][0]);
})",
                      {1.0, 2.0, 3.0}),
              {1.0 + 30.0 + 300.0, 2.0, 3.0 + 10.0});
}

TEST(GlslInterpreter, CommaGivesItsLastValue) {
  EXPECT_EQ(distance_of("float map(vec3 p) { float c = (p.z = 3.0, p.z + 1.0); return c; }"), 4.0);
}

TEST(GlslInterpreter, LaterSideEffectsDoNotChangeEarlierOperands) {
  // Left to right: a's value is read before the assignment on the right runs.
  expect_near(vec3_of(R"(
float g = 1.0;
float bump() { g += 10.0; return 0.0; }
vec3 f(vec3 p) {
  float a = p.x;
  float s = a + (a = 5.0);
  float t = g + bump();
  return vec3(s, t, g);
})",
                      {2.0, 0.0, 0.0}),
              {7.0, 1.0, 11.0});
}

TEST(GlslInterpreter, CompoundAssignmentsWithEveryOperator) {
  expect_near(vec3_of(R"(vec3 f(vec3 p) {
  int i = int(p.x);
  i += 3; i *= 4; i -= 1; i /= 2; i %= 5;
  int j = int(p.x);
  j <<= 4; j >>= 1; j |= 3; j &= 13; j ^= 6;
  uint u = uint(p.y);
  u >>= 1u; u *= 3u;
  vec3 v = p;
  v += 1.0; v *= vec3(2.0); v /= 4.0; v -= p;
  return vec3(float(i) + 10.0 * float(j), float(u), v.z);
})",
                      {1.0, 7.0, 3.0}),
              {2.0 + 10.0 * ((((1 << 4) >> 1 | 3) & 13) ^ 6), 9.0, -1.0});
}

TEST(GlslInterpreter, SwitchFallsThroughToBreakAndDefault) {
  const std::string code = R"(
float map(vec3 p) {
  float r = 0.0;
  switch (int(p.x)) {
    case 0: r += 1.0;
    case 1: r += 10.0; break;
    case 2: r += 100.0;
    default: r += 1000.0;
  }
  return r;
})";
  const Interpreter interpreter = interpreter_of(code);
  EXPECT_EQ(interpreter.distance({0, 0, 0}, 0.0), 11.0);
  EXPECT_EQ(interpreter.distance({1, 0, 0}, 0.0), 10.0);
  EXPECT_EQ(interpreter.distance({2, 0, 0}, 0.0), 1100.0);
  EXPECT_EQ(interpreter.distance({7, 0, 0}, 0.0), 1000.0);
  EXPECT_EQ(distance_of("float map(vec3 p) { switch (int(p.x)) { case 1: return 5.0; } return 3.0; }", {2, 0, 0}), 3.0);
}

TEST(GlslInterpreter, LoopsOfEveryForm) {
  expect_near(vec3_of(R"(vec3 f(vec3 p) {
  float a = 0.0;
  for (int i = 0; i < 10; i++) {
    if (i == 2) continue;
    if (i == 5) break;
    a += float(i);
  }
  float b = 0.0;
  do { b += 1.0; } while (b < p.x);
  float c = 0.0;
  for (;;) { c += 1.0; if (c >= 3.0) break; }
  int k = 0;
  while (k < 4) k++;
  return vec3(a + 10.0 * b, c, float(k));
})",
                      {-1.0, 0.0, 0.0}),
              {8.0 + 10.0, 3.0, 4.0});
}

TEST(GlslInterpreter, LocalsWithoutInitializerAreZeroedWhereDeclared) {
  // As WebGL does: each iteration's z starts at 0.
  EXPECT_EQ(distance_of("float map(vec3 p) { float s = 0.0; for (int i = 0; i < 3; i++) { float z; z += 1.0; s += z; } "
                        "return s; }"),
            3.0);
}

TEST(GlslInterpreter, ARunawayLoopIsAnInputErrorNamingItsLine) {
  const Interpreter interpreter = interpreter_of(R"(float map(vec3 p) {
  float x = 0.0;
  while (p.x < 1.0) { x += 1.0; }
  return x;
})");
  try {
    interpreter.distance({0, 0, 0}, 0.0);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("test.glsl:3:"), std::string::npos) << error.what();
  }
  EXPECT_EQ(interpreter.distance({2, 0, 0}, 0.0), 0.0);
}

TEST(GlslInterpreter, GlobalsAreInitialisedAtEveryCall) {
  const Interpreter interpreter = interpreter_of(R"(
float counter = 1.0;
const float kStep = 2.0;
float bump() { counter += kStep; return counter; }
float map(vec3 p) { bump(); return counter + p.x; })");
  EXPECT_EQ(interpreter.distance({0, 0, 0}, 0.0), 3.0);
  EXPECT_EQ(interpreter.distance({1, 0, 0}, 0.0), 4.0);
}

TEST(GlslInterpreter, UniformsHoldTimeResolutionAndFrame) {
  Source source;
  source.code = R"(
float map(vec3 p) { return 0.0; }
vec3 f(vec3 p) { return vec3(iTime + iMouse.x + iMouse.w, iResolution.x + iResolution.y * 1000.0 + iResolution.z * 1e7,
                             float(iFrame) + iTimeDelta); })";
  source.file_name = "test.glsl";
  source.color_function = "f";
  const Interpreter interpreter(compile(source), UniformValues{320.0, 200.0});
  expect_near(interpreter.color({}, 1.5), {1.5, 320.0 + 200000.0 + 1e7, 90.0 + 1.0 / 60.0});
}

TEST(GlslInterpreter, EveryScalarBuiltinMatchesItsDefinition) {
  struct Case {
    std::string expression;
    std::function<double(double)> expected;
  };
  const double pi = std::acos(-1.0);
  const std::vector<Case> cases = {
      {"radians(x)", [&](double x) { return x * pi / 180.0; }},
      {"degrees(x)", [&](double x) { return x * 180.0 / pi; }},
      {"sin(x)", [](double x) { return std::sin(x); }},
      {"cos(x)", [](double x) { return std::cos(x); }},
      {"tan(x)", [](double x) { return std::tan(x); }},
      {"asin(x * 0.25)", [](double x) { return std::asin(x * 0.25); }},
      {"acos(x * 0.25)", [](double x) { return std::acos(x * 0.25); }},
      {"atan(x)", [](double x) { return std::atan(x); }},
      {"atan(x, -0.5)", [](double x) { return std::atan2(x, -0.5); }},
      {"sinh(x)", [](double x) { return std::sinh(x); }},
      {"cosh(x)", [](double x) { return std::cosh(x); }},
      {"tanh(x)", [](double x) { return std::tanh(x); }},
      {"asinh(x)", [](double x) { return std::asinh(x); }},
      {"acosh(abs(x) + 1.0)", [](double x) { return std::acosh(std::abs(x) + 1.0); }},
      {"atanh(x * 0.25)", [](double x) { return std::atanh(x * 0.25); }},
      {"pow(abs(x), 1.5)", [](double x) { return std::pow(std::abs(x), 1.5); }},
      {"exp(x)", [](double x) { return std::exp(x); }},
      {"log(abs(x))", [](double x) { return std::log(std::abs(x)); }},
      {"exp2(x)", [](double x) { return std::exp2(x); }},
      {"log2(abs(x))", [](double x) { return std::log2(std::abs(x)); }},
      {"sqrt(abs(x))", [](double x) { return std::sqrt(std::abs(x)); }},
      {"inversesqrt(abs(x))", [](double x) { return 1.0 / std::sqrt(std::abs(x)); }},
      {"abs(x)", [](double x) { return std::abs(x); }},
      {"sign(x)", [](double x) { return x > 0   ? 1.0
                                        : x < 0 ? -1.0
                                                : 0.0; }},
      {"floor(x)", [](double x) { return std::floor(x); }},
      {"trunc(x)", [](double x) { return std::trunc(x); }},
      {"ceil(x)", [](double x) { return std::ceil(x); }},
      {"min(x, 0.25)", [](double x) { return std::min(x, 0.25); }},
      {"max(x, 0.25)", [](double x) { return std::max(x, 0.25); }},
      {"clamp(x, -1.0, 1.0)", [](double x) { return std::clamp(x, -1.0, 1.0); }},
      {"mix(2.0, 5.0, x)", [](double x) { return 2.0 * (1.0 - x) + 5.0 * x; }},
      {"step(0.25, x)", [](double x) { return x < 0.25 ? 0.0 : 1.0; }},
      {"smoothstep(-1.0, 1.0, x)",
       [](double x) {
         const double t = std::clamp((x + 1.0) / 2.0, 0.0, 1.0);
         return t * t * (3.0 - 2.0 * t);
       }},
      {"length(vec2(x, 2.0))", [](double x) { return std::sqrt(x * x + 4.0); }},
      {"distance(vec2(x, 2.0), vec2(1.0, -1.0))", [](double x) { return std::sqrt((x - 1) * (x - 1) + 9.0); }},
      {"dot(vec3(x, 2.0, 1.0), vec3(3.0, x, -1.0))", [](double x) { return 5.0 * x - 1.0; }},
      {"cross(vec3(x, 2.0, 1.0), vec3(3.0, x, -1.0)).y", [](double x) { return 3.0 + x; }},
      {"normalize(vec2(x, 1.0)).x", [](double x) { return x / std::sqrt(x * x + 1.0); }},
      {"faceforward(vec2(x, 1.0), vec2(1.0), vec2(-1.0, x)).y", [](double x) { return x - 1.0 < 0 ? 1.0 : -1.0; }},
      {"reflect(vec2(x, 1.0), vec2(0.0, 1.0)).y", [](double) { return -1.0; }},
      {"refract(vec2(0.75, -0.5), vec2(0.0, 1.0), abs(x)).x",
       [](double x) {
         const double eta = std::abs(x), d = -0.5, k = 1.0 - eta * eta * (1.0 - d * d);
         return k < 0.0 ? 0.0 : eta * 0.75;
       }},
      {"float(isnan(x / 0.0 - x / 0.0))", [](double) { return 1.0; }},
      {"float(isinf(x / 0.0))", [](double x) { return x == 0.0 ? 0.0 : 1.0; }},
      {"float(floatBitsToInt(x))", [](double x) { return std::bit_cast<std::int32_t>(static_cast<float>(x)); }},
      {"float(floatBitsToUint(x))", [](double x) { return std::bit_cast<std::uint32_t>(static_cast<float>(x)); }},
      {"intBitsToFloat(floatBitsToInt(x))", [](double x) { return static_cast<float>(x); }},
      {"uintBitsToFloat(floatBitsToUint(x))", [](double x) { return static_cast<float>(x); }},
  };
  for (const Case& c : cases) {
    const Interpreter interpreter = interpreter_of("float map(vec3 p) { float x = p.x; return " + c.expression + "; }");
    for (const double x : {-2.75, -0.5, 0.0, 0.1, 1.25, 3.5}) {
      const double expected = c.expected(x), actual = interpreter.distance({x, 0, 0}, 0.0);
      if (std::isnan(expected))
        EXPECT_TRUE(std::isnan(actual)) << c.expression << " at " << x;
      else if (std::isinf(expected))
        EXPECT_EQ(actual, expected) << c.expression << " at " << x;
      else
        EXPECT_NEAR(actual, expected, kTolerance * std::max(1.0, std::abs(expected))) << c.expression << " at " << x;
    }
  }
}

TEST(GlslInterpreter, RoundTakesHalvesToEvenAsLlvmpipe) {
  expect_near(vec3_of("vec3 f(vec3 p) { return round(p); }", {2.5, 3.5, -2.5}), {2.0, 4.0, -2.0});
  expect_near(vec3_of("vec3 f(vec3 p) { return roundEven(p); }", {0.5, 1.5, -1.25}), {0.0, 2.0, -1.0});
}

TEST(GlslInterpreter, ModfWritesItsWholePart) {
  expect_near(vec3_of("vec3 f(vec3 p) { float i; float r = modf(p.x, i); vec2 j; vec2 s = modf(p.yz, j); "
                      "return vec3(r + 10.0 * i, s.x + j.y, j.x); }",
                      {-2.75, 1.5, 3.25}),
              {-0.75 - 20.0, 0.5 + 3.0, 1.0});
}

TEST(GlslInterpreter, VectorBuiltinsTakeMixedForms) {
  const glm::dvec3 p(-1.5, 0.25, 2.0);
  expect_near(vec3_of("vec3 f(vec3 p) { return min(p, 0.5) + max(p, vec3(0.0)) * 10.0; }", p),
              glm::min(p, 0.5) + glm::max(p, 0.0) * 10.0);
  expect_near(vec3_of("vec3 f(vec3 p) { return clamp(p, -1.0, 1.0) + step(0.25, p) * 10.0; }", p),
              glm::clamp(p, -1.0, 1.0) + glm::step(0.25, p) * 10.0);
  expect_near(vec3_of("vec3 f(vec3 p) { return mix(p, vec3(1.0), 0.25) + smoothstep(0.0, 1.0, p) * 10.0; }", p),
              p * 0.75 + 0.25 + glm::smoothstep(0.0, 1.0, p) * 10.0);
  expect_near(vec3_of("vec3 f(vec3 p) { return mix(vec3(1.0), vec3(2.0), bvec3(true, false, p.z > 0.0)); }", p),
              {2.0, 1.0, 2.0});
  expect_near(vec3_of("vec3 f(vec3 p) { return vec3(lessThan(p, vec3(0.0))) + vec3(equal(p, vec3(2.0))) * 10.0 + "
                      "vec3(not(greaterThanEqual(p, vec3(0.25)))) * 100.0; }",
                      p),
              {101.0, 0.0, 10.0});
  expect_near(vec3_of("vec3 f(vec3 p) { bvec3 b = greaterThan(p, vec3(0.0)); return vec3(float(any(b)), float(all(b)), "
                      "float(all(notEqual(p, vec3(1.0))))) + vec3(lessThanEqual(p, vec3(0.25))) * 10.0; }",
                      p),
              {11.0, 10.0, 1.0});
  expect_near(vec3_of("vec3 f(vec3 p) { return vec3(abs(ivec3(p)) * 10 + sign(ivec3(p))) + vec3(clamp(ivec3(p), "
                      "ivec3(0), ivec3(1))) * 1000.0; }",
                      p),
              {10.0 - 1.0, 0.0, 20.0 + 1.0 + 1000.0});
}

TEST(GlslInterpreter, ConcurrentCallsKeepTheirOwnState) {
  const Interpreter interpreter = interpreter_of(kBox + R"(
float g = 0.0;
float map(vec3 p) {
  for (int i = 0; i < 8; i++) g += p.x;
  return sdBox(p, vec3(g)) + g;
})");
  const auto expected = [](double x) {
    const double g = 8.0 * x;
    return box_distance({x, 0.5, -0.25}, glm::dvec3(g)) + g;
  };
  std::vector<int> failures(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 2000; ++i) {
        const double x = 0.25 + 0.001 * (t * 2000 + i);
        if (std::abs(interpreter.distance({x, 0.5, -0.25}, 0.0) - expected(x)) > kTolerance) ++failures[t];
      }
    });
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(failures[t], 0) << "thread " << t;
}

// IR built by hand, for what the interpreter must do whatever the front end makes of the source.
const Type kFloat{Scalar::Float};
const Type kVec3{Scalar::Float, 3};

/// A module of `map(vec3 p)` (variable 0) with the other variables given, map's body to come.
Module module_ir(const std::vector<std::pair<std::string, Type>>& locals) {
  Module module;
  module.file_name = "test.glsl";
  module.variables.push_back({"p", kVec3, Storage::Parameter, ParameterQualifier::In, UniformKind::None, {}});
  for (const auto& [name, type] : locals)
    module.variables.push_back({name, type, Storage::Local, ParameterQualifier::In, UniformKind::None, {}});
  module.functions.push_back({"map", kFloat, {0}, Stmt{}, {4, 1}});
  module.distance_function = 0;
  return module;
}

Expr expr_ir(ExprKind kind, Type type, std::vector<Expr> operands = {}) {
  Expr expr;
  expr.kind = kind;
  expr.type = type;
  expr.operands = std::move(operands);
  return expr;
}

Expr variable_ir(int variable, Type type = kFloat) {
  Expr expr = expr_ir(ExprKind::Variable, type);
  expr.variable = variable;
  return expr;
}

Expr constant_ir(double value) {
  Expr expr = expr_ir(ExprKind::Constant, kFloat);
  expr.constant = {value};
  return expr;
}

/// left op right, or left op= right where kind is Assign.
Expr binary_ir(ExprKind kind, Operator op, Expr left, Expr right, Type type = kFloat) {
  Expr expr = expr_ir(kind, type, {std::move(left), std::move(right)});
  expr.op = op;
  expr.compound = kind == ExprKind::Assign;
  return expr;
}

Stmt statement_ir(StmtKind kind, Expr expression = {}, std::vector<Stmt> body = {}) {
  Stmt stmt;
  stmt.kind = kind;
  stmt.expression = std::move(expression);
  stmt.has_value = kind == StmtKind::Return;
  stmt.body = std::move(body);
  return stmt;
}

Stmt declaration_ir(int variable) {
  Stmt stmt = statement_ir(StmtKind::Declaration);
  stmt.variable = variable;
  return stmt;
}

TEST(GlslInterpreter, DeclarationsZeroTheirVariableEachTimeTheyRun) {
  // float map(vec3 p) { float s; while (s < 5.0) { float z; z += 1.0; s += z; } return (s *= 10.0, s + 1.0); }
  // Each iteration's z starts at 0: 5 iterations, s = 5 (z kept would give 1, 3, 6).
  Module module = module_ir({{"s", kFloat}, {"z", kFloat}});
  const Expr s = variable_ir(1), z = variable_ir(2);
  Stmt loop = statement_ir(
      StmtKind::Loop, binary_ir(ExprKind::Operation, Operator::Less, s, constant_ir(5.0), Type{Scalar::Bool}),
      {statement_ir(
          StmtKind::Block, {},
          {declaration_ir(2),
           statement_ir(StmtKind::Expression, binary_ir(ExprKind::Assign, Operator::Add, z, constant_ir(1.0))),
           statement_ir(StmtKind::Expression, binary_ir(ExprKind::Assign, Operator::Add, s, z))})});
  const Expr comma = expr_ir(ExprKind::Comma, kFloat,
                             {binary_ir(ExprKind::Assign, Operator::Multiply, s, constant_ir(10.0)),
                              binary_ir(ExprKind::Operation, Operator::Add, s, constant_ir(1.0))});
  module.functions[0].body =
      statement_ir(StmtKind::Block, {}, {declaration_ir(1), loop, statement_ir(StmtKind::Return, comma)});
  EXPECT_EQ(Interpreter(module, UniformValues{}).distance({}, 0.0), 51.0);
}

TEST(GlslInterpreter, RecursionIsRefused) {
  // glslang finds recursion only when linking, so the interpreter checks what it is given.
  Module module = module_ir({});
  Expr call = expr_ir(ExprKind::Call, kFloat, {variable_ir(0, kVec3)});
  call.function = 0;
  module.functions[0].body = statement_ir(StmtKind::Return, call);
  try {
    const Interpreter interpreter(module, UniformValues{});
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "test.glsl:4:1: 'map' calls itself, directly or through other functions; GLSL forbids recursion");
  }
}

}  // namespace
}  // namespace clmarch::glsl

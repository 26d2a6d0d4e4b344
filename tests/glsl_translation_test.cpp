// The OpenCL translation of user GLSL: snippets compiled by the front end, translated, built on
// the device inside a kernel that evaluates the entry point at points and times, and compared with
// closed forms written here (in float and in double) and with the double-precision interpreter.
#include "cl/device_program.hpp"
#include "glsl/glsl_front_end.hpp"
#include "glsl/glsl_interpreter.hpp"
#include "glsl/opencl_translation.hpp"
#include "support/evaluate_kernel.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_access.hpp>

#include <cmath>
#include <functional>
#include <optional>
#include <random>

namespace clmarch {
namespace {

using glm::dvec3;

// Float: the snippets' values are sums of a few terms each within a few float ulps; relative to
// the value's magnitude (at least 1), 2^-18 leaves room for their rounding without hiding a
// wrong term (the terms are spread over decimal digits, so a wrong one moves the value by >= 0.1).
constexpr double kFloatTolerance = 4e-6;
// Double: the same operations in double (OpenCL's built-ins are within a few ulps).
constexpr double kDoubleTolerance = 1e-12;
// The interpreter against the double translation: the same formulas, different libm.
constexpr double kInterpreterTolerance = 1e-10;

struct Probe {
  dvec3 p;
  double t = 0.0;
};

struct Snippet {
  std::string name;
  std::string code;
  std::vector<Probe> probes;
  std::function<double(const dvec3& p, double t)> expected;
};

// The translation's entry point at each probe, in the precision asked for.
std::vector<double> evaluate_on_device(const glsl::Module& module, bool double_precision,
                                       const std::vector<Probe>& probes, bool color = false) {
  glsl::TranslationOptions options;
  options.double_precision = double_precision;
  const std::string real = double_precision ? "double" : "float";
  std::string source = double_precision ? "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n" : "";
  source += glsl::translate_to_opencl(module, options);
  source += "\n#line 1 \"glsl_translation_test\"\n";
  if (color) {
    source += fmt::format(
        "kernel void evaluate(global const {0}* in, global {0}* out) {{\n"
        "  size_t i = get_global_id(0);\n"
        "  {0}3 c = glsl0_color(({0}3)(in[4 * i], in[4 * i + 1], in[4 * i + 2]), in[4 * i + 3]);\n"
        "  out[3 * i] = c.x; out[3 * i + 1] = c.y; out[3 * i + 2] = c.z;\n}}\n",
        real);
  } else {
    source += fmt::format(
        "kernel void evaluate(global const {0}* in, global {0}* out) {{\n"
        "  size_t i = get_global_id(0);\n"
        "  out[i] = glsl0_distance(({0}3)(in[4 * i], in[4 * i + 1], in[4 * i + 2]), in[4 * i + 3]);\n}}\n",
        real);
  }
  std::vector<double> in;
  for (const Probe& probe : probes) in.insert(in.end(), {probe.p.x, probe.p.y, probe.p.z, probe.t});
  return testing::run_evaluate_kernel(source, in, probes.size(), probes.size() * (color ? 3 : 1), double_precision);
}

glsl::Module compiled(const std::string& name, const std::string& code, const std::string& color_function = "") {
  glsl::Source source;
  source.code = code;
  source.file_name = name + ".glsl";
  source.color_function = color_function;
  return glsl::compile(source);
}

double box(const dvec3& p, const dvec3& b) {
  const dvec3 q = glm::abs(p) - b;
  return glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}

double glsl_mod(double x, double y) { return x - y * std::floor(x / y); }

const std::vector<Probe> kProbes = {
    {{0.5, 0.25, -1.5}, 0.0}, {{-2.0, 1.0, 0.75}, 0.5}, {{1.25, -0.5, 3.0}, 1.25}, {{-0.25, -1.75, -2.5}, 2.0}};

const std::vector<Snippet>& snippets() {
  static const std::vector<Snippet> all = {
      {"rotated_box",
       R"(mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }
float sdBox(vec3 p, vec3 b) { vec3 q = abs(p) - b; return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0); }
float map(vec3 p) { p.xz *= rot(0.5); return sdBox(p, vec3(1.0, 0.5, 0.75)); })",
       kProbes,
       [](const dvec3& p, double) {
         // p.xz * m = (dot(p.xz, column 0), dot(p.xz, column 1)) = transpose(m) p.xz.
         const double c = std::cos(0.5), s = std::sin(0.5);
         return box({p.x * c + p.z * s, p.y, -p.x * s + p.z * c}, {1.0, 0.5, 0.75});
       }},
      {"mod_fract_of_negatives",
       "float map(vec3 p) { return mod(p.x, 1.5) + 10.0 * mod(p.z, -2.0) + 100.0 * fract(p.y) + "
       "1000.0 * mod(p, vec3(0.7)).y; }",
       kProbes,
       [](const dvec3& p, double) {
         return glsl_mod(p.x, 1.5) + 10.0 * glsl_mod(p.z, -2.0) + 100.0 * (p.y - std::floor(p.y)) +
                1000.0 * glsl_mod(p.y, 0.7);
       }},
      // Copy-in and copy-out of a swizzle, the left operand read before the call writes p.
      {"swizzle_inout_write_back",
       R"(float g(inout vec2 v, float a) { v += a; v.x *= 2.0; return v.y; }
void pR(inout vec2 p, float a) { p = cos(a) * p + sin(a) * vec2(p.y, -p.x); }
float map(vec3 p) {
  float d = p.x + g(p.zx, 1.0);
  pR(p.xy, 0.25);
  return d + 10.0 * p.x + 100.0 * p.z + 1000.0 * p.y;
})",
       kProbes,
       [](const dvec3& q, double) {
         dvec3 p = q;
         const double d = p.x + (p.x + 1.0);
         p.z = 2.0 * (p.z + 1.0);
         p.x = p.x + 1.0;
         const double c = std::cos(0.25), s = std::sin(0.25);
         const double x = c * p.x + s * p.y, y = c * p.y - s * p.x;
         return d + 10.0 * x + 100.0 * p.z + 1000.0 * y;
       }},
      {"integer_wrap_and_division",
       R"(float map(vec3 p) {
  int big = 2147483647;
  big += int(p.y > -10.0);            // INT_MAX + 1 wraps to INT_MIN
  int product = 65536 * 65536 + 3;     // 2^32 + 3 wraps to 3
  int zero = int(p.x * 0.0);
  int by_zero = 7 / zero + 7 % zero;  // defined here as 0
  int min_over = big / -1;            // INT_MIN / -1 wraps to INT_MIN
  uint u = 0u - 1u;
  int shifted = (1 << 31) >> 3;       // arithmetic shift of INT_MIN
  return float(big == -2147483647 - 1) + 10.0 * float(product) + 100.0 * float(by_zero + 1)
       + 1000.0 * float(min_over == big) + 1e4 * float(u == 4294967295u) + 1e5 * float(shifted == -268435456)
       + 1e6 * float(-7 / 2) + 1e7 * float(abs(-5) + (6 & 3) + (4 | 1) + (6 ^ 5));
})",
       kProbes,
       [](const dvec3&, double) { return 1.0 + 30.0 + 100.0 + 1000.0 + 1e4 + 1e5 - 3e6 + 1e7 * (5 + 2 + 5 + 3); }},
      // Names that are OpenCL C keywords, built-ins, the kernels' macros or the translation's own
      // words; shadowing (GLSL's scope begins after the initialiser, C's before).
      {"name_collisions",
       R"(struct local { float global; int constant; };
float select(float kernel) { return kernel * 2.0; }
float select(vec2 private_) { return private_.x + private_.y; }
float sincos(float read_only) { float image2d_t = read_only; float event_t = 1.0; float sampler_t = 2.0; return image2d_t + event_t + sampler_t; }
float map(vec3 p) {
  float vec_step = 1.0; float as_float = 2.0; float real = 3.0; float vfloat = 4.0; float LANES = 5.0;
  float MASK = 6.0; float tmp1 = 7.0; float globals = 8.0; float t = 9.0; float float3 = 10.0; float M_PI = 11.0;
  float INFINITY = 12.0; float glsl0_map = 13.0; float p_ = 14.0; float first1 = 15.0;
  local l = local(16.0, 17);
  float d = 1.0;
  { float d = d + 1.0; vec_step += d; }
  return vec_step + as_float + real + vfloat + LANES + MASK + tmp1 + globals + t + float3 + M_PI + INFINITY
       + glsl0_map + p_ + first1 + l.global + float(l.constant) + select(1.0) + select(vec2(1.0, 2.0)) + sincos(0.5) + p.x * 0.0 + d;
})",
       kProbes, [](const dvec3&, double) { return 164.5; }},
      // Evaluation order and short-circuits around calls with side effects, loops whose condition
      // writes, increments of scalars, vectors and swizzles.
      {"side_effects_in_order",
       R"(float counter = 0.0;
float bump() { counter += 1.0; return counter; }
bool inc(inout int n) { n++; return true; }
bool step_it(inout int i) { i++; return i < 5; }
float map(vec3 p) {
  float d = 0.0;
  int n = 0;
  if (p.y < 0.0 && inc(n)) d += 1.0;
  bool b = p.y > 0.0 || inc(n);
  float s = p.y > 0.0 ? bump() : -bump();
  int i = 0; int loops = 0;
  while (step_it(i)) { loops++; if (loops > 50) break; }
  do { loops += 10; } while (inc(n) && n < 4);
  for (int k = 0; k < 3; k++) { n += 10; if (k == 1) continue; d += 0.5; }
  vec3 v = vec3(1.0); v++; v.yz--; float post = v.x++ + v.x;
  ivec2 iv = ivec2(3); int pre = ++iv.y * 2;
  return d + float(n) * 10.0 + s * 1000.0 + float(loops) * 1e4 + counter * 1e6 + post * 1e7 + float(pre) * 1e8 + (b ? 0.0 : 1e9);
})",
       kProbes,
       [](const dvec3& p, double) {
         int n = 0;
         double d = 0.0;
         if (p.y < 0.0) d += 1.0, ++n;
         if (!(p.y > 0.0)) ++n;
         const double s = p.y > 0.0 ? 1.0 : -1.0;
         int loops = 4;
         do {
           loops += 10;
           ++n;
         } while (n < 4);
         n += 30;
         d += 1.0;
         return d + n * 10.0 + s * 1000.0 + loops * 1e4 + 1e6 + 5.0 * 1e7 + 8.0 * 1e8;
       }},
      {"matrices",
       R"(float map(vec3 p) {
  mat2 m = mat2(1.0, 2.0, 3.0, 4.0);
  mat3 r = mat3(2.0, 0.0, 1.0, 1.0, 3.0, 0.0, 0.0, 1.0, 4.0);
  mat3 ri = inverse(r) * r;
  vec2 mv = m * vec2(1.0, 2.0);
  vec2 vm = vec2(1.0, 2.0) * m;
  mat2 mm = m * m;
  mat2 ms = m * 2.0 + m - m / 2.0;
  mat2 neg = -m;
  mat2x3 nonsq = mat2x3(1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
  vec3 ns = nonsq * vec2(1.0, -1.0);
  mat3x2 tr = transpose(nonsq);
  mat2 op = outerProduct(vec2(1.0, 2.0), vec2(3.0, 4.0));
  mat2 cm = matrixCompMult(m, m);
  float eq = (m == mat2(1.0, 2.0, 3.0, 4.0)) ? 1.0 : 0.0;
  mat4 m4 = mat4(2.0); m4[3] = vec4(1.0, 2.0, 3.0, 1.0);
  mat4 m4i = inverse(m4);
  mat3 m3 = mat3(m4);
  int i = int(p.x > 0.0);
  float dynamic = m[i][1 - i] + mv[i];
  m[i][i] = 9.0;
  vec4 v4 = vec4(m);
  return ri[0][0] + ri[1][1] + ri[2][2] + ri[0][1] + ri[2][0] + mv.x * 10.0 + mv.y * 100.0 + vm.x * 1e3 + vm.y * 1e4
    + mm[1][0] * 1e5 + ms[1][1] + neg[0][1] + ns.z * 3.0 + tr[2][1] + op[1][0] + cm[1][1] + eq + determinant(m)
    + determinant(r) + m4i[3][0] + m3[2][2] + dynamic * 1e6 + v4.w * 7.0 + v4.x * 1e7;
})",
       kProbes,
       [](const dvec3& p, double) {
         glm::dmat2 m(1, 2, 3, 4);
         const glm::dmat3 r(2, 0, 1, 1, 3, 0, 0, 1, 4);
         const glm::dmat3 ri = glm::inverse(r) * r;
         const glm::dvec2 mv = m * glm::dvec2(1, 2), vm = glm::dvec2(1, 2) * m;
         const glm::dmat2 mm = m * m, ms = m * 2.0 + m - m / 2.0, neg = -m;
         const glm::dmat2x3 nonsq(1, 2, 3, 4, 5, 6);
         const glm::dvec3 ns = nonsq * glm::dvec2(1, -1);
         const glm::dmat3x2 tr = glm::transpose(nonsq);
         const glm::dmat2 op = glm::outerProduct(glm::dvec2(1, 2), glm::dvec2(3, 4));
         const glm::dmat2 cm = glm::matrixCompMult(m, m);
         glm::dmat4 m4(2.0);
         m4[3] = glm::dvec4(1, 2, 3, 1);
         const glm::dmat4 m4i = glm::inverse(m4);
         const int i = p.x > 0.0 ? 1 : 0;
         const double dynamic = m[i][1 - i] + mv[i];
         m[i][i] = 9.0;
         return ri[0][0] + ri[1][1] + ri[2][2] + ri[0][1] + ri[2][0] + mv.x * 10 + mv.y * 100 + vm.x * 1e3 +
                vm.y * 1e4 + mm[1][0] * 1e5 + ms[1][1] + neg[0][1] + ns.z * 3 + tr[2][1] + op[1][0] + cm[1][1] + 1.0 +
                glm::determinant(m) + glm::determinant(r) + m4i[3][0] + 2.0 + dynamic * 1e6 + m[1][1] * 7 +
                m[0][0] * 1e7;
       }},
      {"builtins",
       R"(float map(vec3 p) {
  vec3 s = step(0.0, p);
  vec3 c = clamp(p, -1.0, 1.0);
  float sm = smoothstep(1.0, -1.0, p.x);   // reversed edges, GLSL's formula
  vec3 mx = mix(p, vec3(1.0), 0.25);
  vec3 mb = mix(vec3(1.0), vec3(2.0), lessThan(p, vec3(0.0)));
  float h = p.x * 0.0 + 0.5;  // not a constant: glslang folds round() as half away from zero
  float r = round(h + 2.0) + roundEven(h + 3.0) + round(-h) + trunc(-h - 1.0) + ceil(h - 0.25);
  float angles = atan(p.y, p.x) + degrees(radians(30.0)) + inversesqrt(4.0);
  float bits = float(floatBitsToInt(1.0) == 1065353216) + intBitsToFloat(1073741824) + uintBitsToFloat(floatBitsToUint(0.5));
  float whole; vec2 w2;
  float f = modf(p.x, whole) + modf(vec2(p.z, 2.5), w2).y;
  vec3 n = normalize(vec3(1.0, 2.0, 2.0));
  vec3 ff = faceforward(n, vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0));
  vec3 rf = reflect(vec3(1.0, -1.0, 0.0), vec3(0.0, 1.0, 0.0));
  vec3 rr = refract(vec3(0.0, -1.0, 0.0), vec3(0.0, 1.0, 0.0), 0.5);
  bvec3 b = greaterThan(p, vec3(0.0));
  float logic = float(any(b)) + 2.0 * float(all(b)) + 4.0 * float(not(b).x) + 8.0 * float(equal(b, not(not(b))).y);
  return s.x + 2.0 * s.y + 4.0 * s.z + c.x + c.z + sm + mx.y + mb.x + 10.0 * mb.z + r * 100.0 + angles + bits
    + (f + whole + w2.x + w2.y) * 1e3 + n.y + ff.z + rf.y + rr.y + logic * 1e4 + length(-3.0) + distance(1.0, 4.0)
    + sign(p.x) + float(sign(-3)) + dot(2.0, 3.0) + cross(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0)).z
    + pow(2.0, 3.0) + exp2(2.0) + log2(8.0) + sqrt(16.0) + abs(-2.0) + min(p.y, 0.5) + max(p.z, -1.0);
})",
       kProbes,
       [](const dvec3& p, double) {
         const double s = (p.x >= 0 ? 1 : 0) + 2.0 * (p.y >= 0 ? 1 : 0) + 4.0 * (p.z >= 0 ? 1 : 0);
         const double c = std::clamp(p.x, -1.0, 1.0) + std::clamp(p.z, -1.0, 1.0);
         const double t = std::clamp((p.x - 1.0) / -2.0, 0.0, 1.0);
         const double sm = t * t * (3 - 2 * t);
         const double mx = p.y * 0.75 + 0.25;
         const double mb = (p.x < 0 ? 2.0 : 1.0) + 10.0 * (p.z < 0 ? 2.0 : 1.0);
         const double r = 2 + 4 - 0.0 - 1 + 1;
         const double angles = std::atan2(p.y, p.x) + 30.0 + 0.5;
         const double bits = 1.0 + 2.0 + 0.5;
         const double f = (p.x - std::trunc(p.x)) + 0.5 + std::trunc(p.x) + std::trunc(p.z) + 2.0;
         const double n = 2.0 / 3.0;
         const double ff = -(2.0 / 3.0);
         const double rf = 1.0;
         const double rr = -1.0;
         const bool bx = p.x > 0, by = p.y > 0, bz = p.z > 0;
         const double logic = (bx || by || bz ? 1 : 0) + 2.0 * (bx && by && bz ? 1 : 0) + 4.0 * (bx ? 0 : 1) + 8.0;
         const double sign = p.x > 0 ? 1.0 : p.x < 0 ? -1.0 : 0.0;
         return s + c + sm + mx + mb + r * 100 + angles + bits + f * 1e3 + n + ff + rf + rr + logic * 1e4 + 3.0 + 3.0 +
                sign - 1.0 + 6.0 + 1.0 + 8.0 + 4.0 + 3.0 + 4.0 + 2.0 + std::min(p.y, 0.5) + std::max(p.z, -1.0);
       }},
      // Copies: arrays and structs assign, pass and return by value; locals start at zero;
      // dynamic indices read and write vectors and arrays.
      {"aggregates_and_zero_locals",
       R"(struct Hit { float d; vec3 c; float a[2]; };
Hit make(float d) { Hit h; h.d = d; h.c = vec3(d); h.a[1] = 2.0 * d; return h; }
void spoil(float a[3]) { a[0] = 100.0; }
float map(vec3 p) {
  float z; vec3 v; int k; bool b; Hit empty;
  float a[3] = float[3](1.0, 2.0, 3.0);
  float copy[3] = a;
  copy[1] = 20.0;
  spoil(a);
  Hit h = make(p.x);
  Hit g = h;
  g.c.y = 5.0;
  vec4 w = vec4(1.0, 2.0, 3.0, 4.0);
  for (int i = 0; i < 4; ++i) w[i] += float(i) * 10.0;
  int j = int(p.x > 0.0) + 1;
  a[j] = 7.0;
  return z + v.x + float(k) + float(b) + empty.d + empty.a[1] + a[0] + a[1] * 10.0 + a[2] * 100.0 + copy[1] * 1e3
    + h.c.y * 1e4 + g.c.y * 1e5 + h.a[1] + w.w * 1e6 + float(h == g) + float(copy == float[3](1.0, 20.0, 3.0)) * 2.0;
})",
       kProbes,
       [](const dvec3& p, double) {
         double a[3] = {1.0, 2.0, 3.0};
         a[p.x > 0.0 ? 2 : 1] = 7.0;
         return a[0] + a[1] * 10 + a[2] * 100 + 20.0 * 1e3 + p.x * 1e4 + 5.0 * 1e5 + 2.0 * p.x + 34.0 * 1e6 + 2.0;
       }},
      // Globals initialised per call from other globals and the uniforms; a function writing them.
      {"globals_and_uniforms",
       R"(float g = 2.0;
float h = 6.0;
const float k = 0.5;
void twice() { g *= 2.0; }
float map(vec3 p) {
  twice();
  h += iTime;
  return g + h * 10.0 + k + float(iFrame) * 1e3 + iResolution.x * 1e-3 + iTimeDelta * 60.0 + iMouse.z;
})",
       kProbes,
       [](const dvec3&, double t) { return 4.0 + (6.0 + t) * 10.0 + 0.5 + std::floor(60.0 * t) * 1e3 + 0.64 + 1.0; }},
      // switch with fall-through, bool vectors, uints.
      {"switch_bvec_uint",
       R"(float map(vec3 p) {
  int n = int(floor(p.x)) + 3;
  float r = 0.0;
  switch (n) {
    case 1: r += 1.0;
    case 2: r += 2.0; break;
    case 4: { r += 4.0; break; }
    default: r += 8.0;
  }
  bvec2 b = bvec2(p.y > 0.0, true);
  uvec2 u = uvec2(3u, 5u) << 2u;
  return r + (float(b.x) * 10.0 + float(b == bvec2(true)) * 100.0 + float(u.y) * 1e3 + float(true ^^ b.y) * 1e5);
})",
       kProbes,
       [](const dvec3& p, double) {
         const int n = static_cast<int>(std::floor(p.x)) + 3;
         const double r = n == 1 ? 3.0 : n == 2 ? 2.0 : n == 4 ? 4.0 : 8.0;
         return r + (p.y > 0 ? 110.0 : 0.0) + 20e3;
       }},
  };
  return all;
}

class GlslTranslationSnippet : public ::testing::TestWithParam<size_t> {};

TEST_P(GlslTranslationSnippet, MatchesClosedFormInFloatAndDouble) {
  const Snippet& snippet = snippets()[GetParam()];
  const glsl::Module module = compiled(snippet.name, snippet.code);
  const DeviceEntry device = select_device(std::nullopt);
  for (bool double_precision : {false, true}) {
    if (double_precision && !device.has_fp64()) continue;
    const std::vector<double> values = evaluate_on_device(module, double_precision, snippet.probes);
    const double tolerance = double_precision ? kDoubleTolerance : kFloatTolerance;
    for (size_t i = 0; i < snippet.probes.size(); ++i) {
      const Probe& probe = snippet.probes[i];
      const double expected = snippet.expected(probe.p, probe.t);
      EXPECT_NEAR(values[i], expected, tolerance * std::max(1.0, std::abs(expected)))
          << snippet.name << (double_precision ? " (double)" : " (float)") << " at (" << probe.p.x << ", " << probe.p.y
          << ", " << probe.p.z << "), t " << probe.t;
    }
  }
}

// The translation in double and the interpreter at random points: both read the same IR, so a
// difference is a translation (or interpreter) bug.
TEST_P(GlslTranslationSnippet, AgreesWithTheInterpreter) {
  const Snippet& snippet = snippets()[GetParam()];
  if (!select_device(std::nullopt).has_fp64()) GTEST_SKIP() << "no cl_khr_fp64";
  const glsl::Module module = compiled(snippet.name, snippet.code);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  std::uniform_real_distribution<double> time(0.0, 2.0);
  std::vector<Probe> probes;
  for (int i = 0; i < 64; ++i)
    probes.push_back({{coordinate(random), coordinate(random), coordinate(random)}, time(random)});
  const std::vector<double> values = evaluate_on_device(module, true, probes);
  const glsl::Interpreter interpreter(module, glsl::UniformValues{});
  for (size_t i = 0; i < probes.size(); ++i) {
    const double expected = interpreter.distance(probes[i].p, probes[i].t);
    EXPECT_NEAR(values[i], expected, kInterpreterTolerance * std::max(1.0, std::abs(expected)))
        << snippet.name << " at (" << probes[i].p.x << ", " << probes[i].p.y << ", " << probes[i].p.z << "), t "
        << probes[i].t;
  }
}

INSTANTIATE_TEST_SUITE_P(GlslTranslation, GlslTranslationSnippet, ::testing::Range<size_t>(0, snippets().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) { return snippets()[info.param].name; });

TEST(GlslTranslationColor, ColorFunctionEntryPoint) {
  const glsl::Module module = compiled("color", R"(float map(vec3 p) { return length(p) - 1.0; }
vec3 albedo(vec3 p) { return abs(p) * 0.5 + vec3(0.0, 0.25, iTime); })",
                                       "albedo");
  for (bool double_precision : {false, true}) {
    const std::vector<double> values = evaluate_on_device(module, double_precision, kProbes, true);
    for (size_t i = 0; i < kProbes.size(); ++i) {
      const dvec3 expected = glm::abs(kProbes[i].p) * 0.5 + dvec3(0.0, 0.25, kProbes[i].t);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(values[3 * i + c], expected[c], kFloatTolerance * 4.0);
    }
  }
}

// The entry points and every definition start with the prefix; #line points at the user's file
// where the lines since the last directive do not already.
TEST(GlslTranslationText, PrefixedNamesAndLineDirectives) {
  const std::string code = "float helper(float x) { return x; }\nfloat map(vec3 p) {\n  return helper(p.x);\n}\n";
  glsl::TranslationOptions options;
  options.prefix = "node7";
  const std::string text = glsl::translate_to_opencl(compiled("shapes", code), options);
  EXPECT_NE(text.find("float node7_distance(float3 p, float t)"), std::string::npos) << text;
  EXPECT_NE(text.find("#line 2 \"shapes.glsl\"\nfloat node7_map(float3 p_) {\n  return node7_helper(p_.x);"),
            std::string::npos)
      << text;
  options.double_precision = true;
  const std::string text_double = glsl::translate_to_opencl(compiled("shapes", code), options);
  EXPECT_NE(text_double.find("double node7_distance(double3 p, double t)"), std::string::npos) << text_double;
}

}  // namespace
}  // namespace clmarch

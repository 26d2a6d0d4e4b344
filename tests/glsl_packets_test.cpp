// The packet translation of user GLSL (glsl/opencl_packets): packets of four points, each lane a
// different point (so lanes take different branches of an `if` on the point), evaluated on the
// device in float and in double and held to the double-precision interpreter, which reads the same
// IR without any translation; and the constructs that keep the lane-at-a-time path, by name.
#include "cl/devices.hpp"
#include "glsl/glsl_front_end.hpp"
#include "glsl/glsl_interpreter.hpp"
#include "glsl/opencl_packets.hpp"
#include "support/evaluate_kernel.hpp"

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <glm/glm.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace clmarch {
namespace {

using glm::dvec3;

constexpr int kPacketLanes = 4;
constexpr int kPacketCount = 64;
// Float against the double interpreter: each snippet adds terms scaled by powers of ten so that a
// wrong term moves the value by at least 0.01 of its size; its thirty-odd float operations round
// within about 30 ulps of a value that is at most 1e5, i.e. 4e-6 relative, 1e-5 leaves room.
constexpr double kPacketFloatRelative = 1e-5;
// Double: the same formulas, OpenCL's libm against the host's.
constexpr double kPacketDoubleRelative = 1e-10;

glsl::Module compiled_module(const std::string& name, const std::string& code, const std::string& color_function = "") {
  glsl::Source source;
  source.code = code;
  source.file_name = name + ".glsl";
  source.color_function = color_function;
  return glsl::compile(source);
}

struct PointPacket {
  std::vector<dvec3> points;
  double time = 0.0;
};

// Points on a grid of 2^-8 within [-3, 3]^3, exact in float, so that both sides evaluate the same
// point and a jump of mod, floor or step falls on the same side for both.
std::vector<PointPacket> random_packets() {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> step(-768, 768);
  std::uniform_real_distribution<double> time(0.0, 2.0);
  std::vector<PointPacket> packets(kPacketCount);
  for (PointPacket& packet : packets) {
    for (int lane = 0; lane < kPacketLanes; ++lane)
      packet.points.push_back(dvec3(step(random), step(random), step(random)) / 256.0);
    packet.time = static_cast<float>(time(random));
  }
  return packets;
}

// The packet translation's entry point on every packet (three values a lane for the colour).
std::vector<double> evaluate_packets(const glsl::Module& module, bool double_precision,
                                     const std::vector<PointPacket>& packets, bool color = false) {
  glsl::TranslationOptions options;
  options.double_precision = double_precision;
  const glsl::PacketTranslation translation = glsl::translate_to_packets(module, options);
  EXPECT_EQ(translation.obstacle, "");
  const std::string real = double_precision ? "double" : "float";
  std::string source = double_precision ? "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n" : "";
  // What kernels/lanes.cl defines for four lanes.
  source += fmt::format(
      "#define LANES 4\ntypedef {0} real;\ntypedef {0}4 vfloat;\ntypedef {1}4 vint;\n"
      "typedef struct {{ vfloat x, y, z; }} vec3v;\n",
      real, double_precision ? "long" : "int");
  source += translation.code;
  source += "\n#line 1 \"glsl_packets_test\"\n";
  source += fmt::format(
      "kernel void evaluate(global const {0}* in, global {0}* out) {{\n"
      "  const size_t i = get_global_id(0);\n"
      "  const vfloat x = vload4(0, in + 13 * i), y = vload4(0, in + 13 * i + 4), z = vload4(0, in + 13 * i + 8);\n"
      "  const real t = in[13 * i + 12];\n",
      real);
  source += color ? "  const vec3v c = glsl0_color_packet(x, y, z, t);\n"
                    "  vstore4(c.x, 0, out + 12 * i);\n  vstore4(c.y, 0, out + 12 * i + 4);\n"
                    "  vstore4(c.z, 0, out + 12 * i + 8);\n}\n"
                  : "  vstore4(glsl0_distance_packet(x, y, z, t), 0, out + 4 * i);\n}\n";
  std::vector<double> in;
  for (const PointPacket& packet : packets) {
    for (int axis = 0; axis < 3; ++axis) {
      for (const dvec3& p : packet.points) in.push_back(p[axis]);
    }
    in.push_back(packet.time);
  }
  return testing::run_evaluate_kernel(source, in, packets.size(), packets.size() * kPacketLanes * (color ? 3 : 1),
                                      double_precision);
}

struct PacketSnippet {
  std::string name;
  std::string code;
};

// What the packet translation takes: control flow the same on every lane, an if or ?: on the point
// as masks, globals, out and inout arguments, matrices, and integer work on uniform values.
const std::vector<PacketSnippet>& packet_snippets() {
  static const std::vector<PacketSnippet> all = {
      {"if_else_on_the_point",
       R"(float map(vec3 p) {
  float d = 0.0;
  vec2 res = vec2(10.0, 0.0);
  if (p.x > 0.0) {
    d = p.x * 2.0;
    res = vec2(d, 1.0);
  } else if (p.y > 0.5) {
    d = -p.y;
  } else {
    float inner = 3.0;
    d = inner;
    p.z += 1.0;
  }
  if (d < res.x) res = vec2(d, 2.0);
  if (p.z > 0.25) {
    for (int i = 0; i < 3; i++) d += 0.25 * float(i) * p.y;  // a counter set afresh in the branch
  }
  return res.x + 10.0 * res.y + 100.0 * p.z + 1000.0 * d;
})"},
      {"choices_and_logic",
       R"(float map(vec3 p) {
  float a = (p.x < p.y && p.z > 0.0) ? p.x : p.y;
  float b = (p.x > 1.0 || !(p.y < 0.0)) ? 1.0 : -1.0;
  vec2 c = p.z > p.x ? vec2(p.x, 1.0) : vec2(2.0, p.y);
  float e = (p.y > 0.0 && iTime >= 0.0) ? 1e5 : 0.0;
  return a + 10.0 * b + ((p.x > p.z) ^^ (p.y > 0.0) ? 100.0 : 0.0) + 1000.0 * c.x + 1e4 * c.y + e;
})"},
      {"globals_written",
       R"(float glow = 0.0;
vec3 trap = vec3(1e3);
float part(vec3 p) {
  glow += 0.5;
  trap = min(trap, abs(p));
  return length(p) - 1.0;
}
float map(vec3 p) {
  float d = part(p);
  if (p.y > 0.0) glow += 1.0;
  if (p.x > 0.5) d += part(p * 2.0);  // part's writes to glow and trap kept in these lanes only
  return d + 10.0 * glow + 100.0 * trap.x + 1000.0 * iTime;
})"},
      {"uniform_loops_and_ints",
       R"(#define N 5
float map(vec3 p) {
  float s = 0.0;
  int k = 0;
  for (int i = 0; i < N; i++) {
    if (i == 2) continue;
    s += float(i) * p.x;
    k += i % 3;
    if (i / 2 == 2) break;
  }
  int j = 0;
  do {
    j++;
    s += 0.1 * p.y;
  } while (j < 3);
  switch (k) {
    case 3:
      s += 1000.0;
      break;
    default:
      s -= 1000.0;
  }
  return s + p.z * float(k) + float(int(iTime * 4.0));
})"},
      {"matrices_and_swizzles",
       R"(mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }
float map(vec3 p) {
  p.xz *= rot(p.y);
  mat3 m = mat3(1.0, 2.0, 0.5, p.x, 1.0, 0.0, 0.0, p.z, 1.0);
  vec3 q = m * p + p * m;
  q.xy = q.yx;
  mat3 o = outerProduct(q, vec3(1.0, 2.0, 3.0)) * transpose(m);
  return q.x + 10.0 * q.z + o[1][2] + 0.01 * (m * m)[2].y + mat2(m)[1].x;
})"},
      {"built_ins_of_the_point",
       R"(float map(vec3 p) {
  vec3 a = mod(p, 0.7) + fract(p * 1.3) + step(0.25, p) + smoothstep(vec3(-1.0), vec3(2.0), p);
  vec3 n = normalize(p + vec3(0.1, 0.2, 0.3));
  vec3 r = reflect(vec3(1.0, -1.0, 0.5), n) + cross(n, vec3(0.0, 1.0, 0.0));
  float b = atan(p.y, p.x) + pow(abs(p.z) + 0.5, 1.5) + inversesqrt(dot(p, p) + 1.0) + sign(p.x) + floor(p.y);
  return dot(a, vec3(1.0, 10.0, 100.0)) + dot(r, vec3(1.0, 10.0, 100.0)) + b +
         mix(p.x, p.y, clamp(p.z, 0.0, 1.0)) + distance(p, vec3(1.0)) + max(p.x, 0.5) * min(p.y, -0.5);
})"},
      {"out_and_inout_arguments",
       R"(void split(vec3 p, out float a, inout vec2 b) { a = p.x * 2.0; b += p.yz; }
float map(vec3 p) {
  float a;
  vec2 b = vec2(1.0);
  split(p, a, b);
  split(p * 2.0, a, p.xy);
  return a + 10.0 * b.x + 100.0 * b.y + 1000.0 * p.x + 1e4 * p.y;
})"},
  };
  return all;
}

class GlslPacketSnippet : public ::testing::TestWithParam<size_t> {};

// Every lane against the interpreter at its own point, in float and in double.
TEST_P(GlslPacketSnippet, EveryLaneMatchesTheInterpreter) {
  const PacketSnippet& snippet = packet_snippets()[GetParam()];
  const glsl::Module module = compiled_module(snippet.name, snippet.code);
  const glsl::Interpreter interpreter(module, glsl::UniformValues{});
  const std::vector<PointPacket> packets = random_packets();
  std::vector<double> expected;
  for (const PointPacket& packet : packets) {
    for (const dvec3& p : packet.points) expected.push_back(interpreter.distance(p, packet.time));
  }
  const auto [lowest, highest] = std::minmax_element(expected.begin(), expected.end());
  ASSERT_GT(*highest - *lowest, 1.0) << snippet.name << ": the values must spread for the comparison to check them";
  const DeviceEntry device = select_device(std::nullopt);
  for (bool double_precision : {false, true}) {
    if (double_precision && !device.has_fp64()) continue;
    const std::vector<double> values = evaluate_packets(module, double_precision, packets);
    const double relative = double_precision ? kPacketDoubleRelative : kPacketFloatRelative;
    for (size_t i = 0; i < expected.size(); ++i) {
      const dvec3& p = packets[i / kPacketLanes].points[i % kPacketLanes];
      EXPECT_NEAR(values[i], expected[i], relative * std::max(1.0, std::abs(expected[i])))
          << snippet.name << (double_precision ? " (double)" : " (float)") << " lane " << i % kPacketLanes << " at ("
          << p.x << ", " << p.y << ", " << p.z << "), t " << packets[i / kPacketLanes].time;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(GlslPackets, GlslPacketSnippet, ::testing::Range<size_t>(0, packet_snippets().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return packet_snippets()[info.param].name;
                         });

TEST(GlslPackets, ColorFunctionPerLane) {
  const glsl::Module module = compiled_module("color", R"(float map(vec3 p) { return length(p) - 1.0; }
vec3 albedo(vec3 p) { vec3 c = abs(p) * 0.5; if (p.y > 0.25) c.z = iTime; return c; })",
                                              "albedo");
  const glsl::Interpreter interpreter(module, glsl::UniformValues{});
  const std::vector<PointPacket> packets = random_packets();
  const std::vector<double> values = evaluate_packets(module, false, packets, true);
  for (size_t packet = 0; packet < packets.size(); ++packet) {
    for (int lane = 0; lane < kPacketLanes; ++lane) {
      const dvec3 expected = interpreter.color(packets[packet].points[lane], packets[packet].time);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(values[packet * 12 + c * 4 + lane], expected[c], kPacketFloatRelative * 4.0)
            << "packet " << packet << " lane " << lane << " channel " << c;
      }
    }
  }
}

// Control flow that differs per lane, ints of the point and aggregates keep the lane-at-a-time
// path, and the reason names the construct and its line.
TEST(GlslPackets, WhatStaysOneLaneAtATimeIsNamed) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"float map(vec3 p) {\n  if (p.x > 0.0) return p.x;\n  return p.y;\n}", "line 2: a return, break or continue"},
      {"float map(vec3 p) {\n  float d = p.y;\n  for (int i = 0; i < 4; i++) { if (d > 1.0) break; d += 0.5; }\n"
       "  return d;\n}",
       "line 3: a return, break or continue"},
      {"float map(vec3 p) {\n  float d = p.x;\n  while (d < 1.0) d += 0.25;\n  return d;\n}",
       "line 3: a loop whose end depends on the point"},
      {"float map(vec3 p) {\n  int cell = int(floor(p.x));\n  return float(cell);\n}",
       "line 2: an int or bool computed from the point"},
      {"struct Hit { float d; };\nfloat map(vec3 p) {\n  Hit h = Hit(p.x);\n  return h.d;\n}", "line 3:"},
      {"float map(vec3 p) {\n  float a[2] = float[2](p.x, p.y);\n  return a[1];\n}", "line 2:"},
      {"bool inside(vec3 p) {\n  return p.x > 0.0;\n}\nfloat map(vec3 p) {\n  return inside(p) ? 1.0 : 2.0;\n}",
       "line 2: a bool of the point returned"},
      // k counts the iterations whose lane took the branch: it differs per lane.
      {"float map(vec3 p) {\n  int k = 0;\n  for (int i = 0; i < 3; i++) {\n    if (p.x > float(i)) k += 1;\n  }\n"
       "  return float(k);\n}",
       "line 4: 'k', an int or bool written in an if whose condition depends on the point"},
  };
  for (const auto& [code, reason] : cases) {
    const glsl::PacketTranslation translation = glsl::translate_to_packets(compiled_module("lane", code), {});
    EXPECT_EQ(translation.code, "") << code;
    EXPECT_EQ(translation.obstacle.rfind(reason, 0), 0u) << code << "\ngave: " << translation.obstacle;
  }
}

}  // namespace
}  // namespace clmarch

// Scene expressions with GLSL's scalar functions, each against the C library or GLSL's definition.
#include "scene/expression.hpp"
#include "scene/scene_loader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace clmarch {
namespace {

double at(const std::string& text, double t) { return evaluate_expression(text, {{"t", t}}); }

TEST(Expression, GlslFunctionsMatchTheirDefinitions) {
  for (double t : {-2.75, -0.5, 0.0, 0.3, 1.25, 7.5}) {
    EXPECT_DOUBLE_EQ(at("abs(t)", t), std::abs(t)) << t;
    EXPECT_DOUBLE_EQ(at("sign(t)", t), t > 0 ? 1.0 : t < 0 ? -1.0 : 0.0) << t;
    EXPECT_DOUBLE_EQ(at("floor(t)", t), std::floor(t)) << t;
    EXPECT_DOUBLE_EQ(at("ceil(t)", t), std::ceil(t)) << t;
    EXPECT_DOUBLE_EQ(at("fract(t)", t), t - std::floor(t)) << t;
    // GLSL's mod follows floor, not C's fmod: mod(-2.75, 2) is 1.25.
    EXPECT_DOUBLE_EQ(at("mod(t, 2)", t), t - 2.0 * std::floor(t / 2.0)) << t;
    EXPECT_DOUBLE_EQ(at("min(t, 0.2)", t), std::min(t, 0.2)) << t;
    EXPECT_DOUBLE_EQ(at("max(t, 0.2)", t), std::max(t, 0.2)) << t;
    EXPECT_DOUBLE_EQ(at("clamp(t, -1, 1)", t), std::min(std::max(t, -1.0), 1.0)) << t;
    EXPECT_DOUBLE_EQ(at("mix(2, 5, t)", t), 2.0 * (1.0 - t) + 5.0 * t) << t;
    EXPECT_DOUBLE_EQ(at("step(0.3, t)", t), t < 0.3 ? 0.0 : 1.0) << t;
    const double s = std::min(std::max((t + 1.0) / 2.0, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(at("smoothstep(-1, 1, t)", t), s * s * (3.0 - 2.0 * s)) << t;
    EXPECT_DOUBLE_EQ(at("pow(2, t)", t), std::pow(2.0, t)) << t;
    EXPECT_DOUBLE_EQ(at("exp(t)", t), std::exp(t)) << t;
    EXPECT_DOUBLE_EQ(at("sin(t)", t), std::sin(t)) << t;
    EXPECT_DOUBLE_EQ(at("cos(t)", t), std::cos(t)) << t;
    EXPECT_DOUBLE_EQ(at("tan(t)", t), std::tan(t)) << t;
    EXPECT_DOUBLE_EQ(at("atan(t)", t), std::atan(t)) << t;
    EXPECT_DOUBLE_EQ(at("atan(t, -0.5)", t), std::atan2(t, -0.5)) << t;
    EXPECT_DOUBLE_EQ(at("length(t)", t), std::abs(t)) << t;
    EXPECT_DOUBLE_EQ(at("length(t, 2)", t), std::hypot(t, 2.0)) << t;
    EXPECT_DOUBLE_EQ(at("length(t, 2, -3)", t), std::hypot(t, 2.0, -3.0)) << t;
  }
  for (double t : {0.01, 0.5, 2.0, 9.0}) {
    EXPECT_DOUBLE_EQ(at("sqrt(t)", t), std::sqrt(t)) << t;
    EXPECT_DOUBLE_EQ(at("log(t)", t), std::log(t)) << "GLSL's log is the natural one; " << t;
  }
  for (double t : {-1.0, -0.3, 0.0, 0.8}) {
    EXPECT_DOUBLE_EQ(at("asin(t)", t), std::asin(t)) << t;
    EXPECT_DOUBLE_EQ(at("acos(t)", t), std::acos(t)) << t;
  }
  EXPECT_DOUBLE_EQ(at("pi", 0.0), M_PI);
}

TEST(Expression, ErrorsNameWhatExists) {
  try {
    at("fract2(t)", 0.0);
    FAIL() << "an unknown function evaluated";
  } catch (const ExpressionError& e) {
    const std::string message = e.what();
    for (const char* part : {"fract2", "the variable t", "the constant pi", "fract", "smoothstep", "length"}) {
      EXPECT_NE(message.find(part), std::string::npos) << part << " in " << message;
    }
  }
  EXPECT_THROW(at("length(1, 2, 3, 4)", 0.0), ExpressionError);
  EXPECT_THROW(at("atan(1, 2, 3)", 0.0), ExpressionError);
  EXPECT_THROW(at("clamp(1, 2)", 0.0), ExpressionError);
}

// In a scene: a quoted expression with commas, and GLSL's functions at the scene's time.
TEST(Expression, ScenesUseThemAtTheirTime) {
  const Scene scene = load_scene_text(
      "sdf: {sphere: {radius: \"max(0.1, fract(t))\", center: [\"mod(t, 2)\", 0, 0]}}\n", "s.yaml", {}, 2.75);
  const Sphere& sphere = std::get<Sphere>(scene.sdf.params);
  EXPECT_DOUBLE_EQ(sphere.radius, 0.75);
  EXPECT_DOUBLE_EQ(sphere.center.x, 0.75);
}

}  // namespace
}  // namespace clmarch

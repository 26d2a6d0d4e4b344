// The glsl node in scene files: its keys and their errors, the user's file and line in messages,
// and a bad node through the CLI (one line, exit 2, no output file).
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace clmarch {
namespace {

using testing::error_of;
using testing::run_clmarch;
using testing::scene_from_yaml;
using testing::TempDir;

TEST(GlslNode, ReadsInlineCodeWithItsSettings) {
  const Scene scene = scene_from_yaml(
      "sdf:\n"
      "  glsl:\n"
      "    code: |\n"
      "      float map(vec3 p) { return length(p) - R; }\n"
      "      vec3 albedo(vec3 p) { return vec3(1.0, 0.5, 0.0); }\n"
      "    defines: {R: 0.75}\n"
      "    lipschitz: 2\n"
      "    bounds: {center: [0, 1, 0], radius: 3}\n"
      "    color: albedo\n");
  ASSERT_EQ(scene.sdf.kind, NodeKind::Glsl);
  const Glsl& glsl = params_of<Glsl>(scene.sdf);
  EXPECT_EQ(glsl.lipschitz, 2.0);
  ASSERT_TRUE(glsl.program->bounds_center);
  EXPECT_EQ(*glsl.program->bounds_center, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_EQ(glsl.program->bounds_radius, 3.0);
  EXPECT_GE(glsl.program->module.color_function, 0);
  EXPECT_FALSE(scene.sdf.color) << "color: albedo names the code's function, not a colour";
  EXPECT_FALSE(scene.animated);
}

TEST(GlslNode, CodeThatReadsTheTimeMakesAnAnimation) {
  const Scene scene = scene_from_yaml("sdf: {glsl: {code: 'float map(vec3 p) { return length(p) - iTime; }'}}\n", 0.5);
  EXPECT_TRUE(scene.animated);
  EXPECT_EQ(params_of<Glsl>(scene.sdf).program->time, 0.5);
}

TEST(GlslNode, AColorIsStillAColor) {
  const Scene scene = scene_from_yaml("sdf: {glsl: {code: 'float map(vec3 p) { return p.y; }', color: [1, 0, 0]}}\n");
  ASSERT_TRUE(scene.sdf.color);
  EXPECT_EQ(*scene.sdf.color, glm::dvec3(1.0, 0.0, 0.0));
  EXPECT_EQ(params_of<Glsl>(scene.sdf).program->module.color_function, -1);
}

TEST(GlslNode, EveryBadKeyIsOneLineNamingIt) {
  EXPECT_EQ(error_of("sdf: {glsl: {function: map}}\n"),
            "s.yaml:1:13: sdf.glsl needs file (a .glsl file) or code (the GLSL text) giving its distance function");
  EXPECT_EQ(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', file: a.glsl}}\n"),
            "s.yaml:1:20: sdf.glsl: give either file or code, not both");
  EXPECT_NE(error_of("sdf: {glsl: {file: missing.glsl}}\n").find("s.yaml:1:20: sdf.glsl.file: cannot read"),
            std::string::npos);
  EXPECT_NE(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', lipschitz: 0}}\n")
                .find("sdf.glsl.lipschitz must be > 0 (got 0)"),
            std::string::npos);
  EXPECT_EQ(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', function: 'm a p'}}\n"),
            "s.yaml:1:67: sdf.glsl.function must name a GLSL function (got 'm a p')");
  EXPECT_NE(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', defines: [1]}}\n")
                .find("sdf.glsl.defines must be a map of names to values"),
            std::string::npos);
  EXPECT_NE(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', bounds: {radius: -1}}}\n")
                .find("sdf.glsl.bounds.radius must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', fucntion: map}}\n").find("fucntion"),
            std::string::npos);
}

TEST(GlslNode, InlineCodeErrorsNameTheSceneFileAndItsLine) {
  EXPECT_EQ(error_of("sdf:\n"
                     "  glsl:\n"
                     "    code: |\n"
                     "      float map(vec3 p) {\n"
                     "        return foo(p);\n"
                     "      }\n"),
            "s.yaml:5:10: 'foo' : no matching overloaded function found");
  EXPECT_EQ(error_of("sdf: {glsl: {code: 'float sdf(vec3 p) { return 1.0; }'}}\n"),
            "s.yaml: no function float, vec2, vec3 or vec4 map(vec3)");
  EXPECT_EQ(error_of("sdf: {glsl: {code: 'float map(vec3 p) { return 1.0; }', function: sdf}}\n"),
            "s.yaml: no function float, vec2, vec3 or vec4 sdf(vec3)");
}

TEST(GlslNode, FileCodeErrorsNameTheGlslFile) {
  TempDir dir;
  std::ofstream(dir / "shapes.glsl") << "float map(vec3 p) {\n  return length(p) - 1.0;\n}\n"
                                        "float broken(vec3 p) {\n  return bar(p);\n}\n";
  std::ofstream(dir / "scene.yaml") << "sdf: {glsl: {file: shapes.glsl}}\nrender: {width: 16, height: 8}\n";
  const testing::CommandResult result =
      run_clmarch({"render", (dir / "scene.yaml").string(), "-o", (dir / "out.png").string()});
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(result.err, (dir / "shapes.glsl").string() + ":5:10: 'bar' : no matching overloaded function found\n");
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"scene.yaml", "shapes.glsl"})) << "no output file";
}

}  // namespace
}  // namespace clmarch

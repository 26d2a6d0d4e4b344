// The scene loader: defaults, JSON, --set overrides and the errors of each rule.
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

namespace clmarch {
namespace {

using testing::scene_from_yaml;

using testing::error_of;

TEST(SceneLoader, DefaultsOfTheContract) {
  const Scene scene = scene_from_yaml("sdf: {sphere: {}}\n");
  EXPECT_EQ(scene.camera.position, glm::dvec3(-2, 4, 4));
  EXPECT_EQ(scene.camera.fov_degrees, 45.0);
  EXPECT_EQ(scene.render.width, 640);
  EXPECT_EQ(scene.render.height, 360);
  EXPECT_EQ(scene.render.max_steps, 255);
  EXPECT_EQ(scene.render.epsilon, 1e-4);
  EXPECT_EQ(scene.render.max_distance, 100.0);
  EXPECT_EQ(std::get<Sphere>(scene.sdf.params).radius, 1.0);
}

TEST(SceneLoader, ContractExampleOfTheIssue) {
  const Scene scene = scene_from_yaml(R"(
camera:   {position: [-2, 4, 4], look_at: [0, 0, 0], up: [0, 1, 0], fov: 45}
render:   {width: 640, height: 360, max_steps: 255, epsilon: 1.0e-4, max_distance: 100}
sdf:
  union:
    - sphere: {center: [0, 0, 0], radius: 1}
    - box:    {center: [2, 0, 0], half_size: [0.5, 0.5, 0.5]}
    - torus:  {center: [-2, 0, 0], major_radius: 1, minor_radius: 0.3}
    - plane:  {normal: [0, 1, 0], offset: 1}
)");
  ASSERT_EQ(scene.sdf.kind, NodeKind::Union);
  ASSERT_EQ(scene.sdf.children.size(), 4u);
  EXPECT_EQ(std::get<Torus>(scene.sdf.children[2].params).minor_radius, 0.3);
  EXPECT_EQ(std::get<Plane>(scene.sdf.children[3].params).offset, 1.0);
}

TEST(SceneLoader, AcceptsJson) {
  const Scene scene =
      scene_from_yaml(R"({"render": {"width": 32, "height": 16}, "sdf": {"box": {"half_size": [1, 2, 3]}}})");
  EXPECT_EQ(scene.render.width, 32);
  EXPECT_EQ(std::get<Box>(scene.sdf.params).half_size, glm::dvec3(1, 2, 3));
}

TEST(SceneLoader, NormalisesPlaneNormalsAndLightDirections) {
  const Scene scene =
      scene_from_yaml("sdf: {plane: {normal: [0, 3, 4]}}\nlights: [{directional: {direction: [2, 0, 0]}}]\n");
  EXPECT_NEAR(glm::length(std::get<Plane>(scene.sdf.params).normal), 1.0, 1e-15);
  EXPECT_EQ(scene.lights[0].direction, glm::dvec3(1, 0, 0));
}

TEST(SceneLoader, OverridesReachAnyKey) {
  const std::string yaml = "sdf: {union: [{sphere: {radius: 1}}, {box: {}}]}\n";
  const Scene scene = load_scene_text(yaml, "s.yaml",
                                      {{"render.epsilon", "1e-5"},
                                       {"camera.position", "[0, 0, 1e6]"},
                                       {"sdf.union.0.sphere.radius", "2.5"},
                                       {"shading.view", "normals"}});
  EXPECT_EQ(scene.render.epsilon, 1e-5);
  EXPECT_EQ(scene.camera.position, glm::dvec3(0, 0, 1e6));
  EXPECT_EQ(std::get<Sphere>(scene.sdf.children[0].params).radius, 2.5);
  EXPECT_EQ(scene.shading.view, View::Normals);
}

TEST(SceneLoader, OverrideErrorsNameTheOption) {
  const std::string yaml = "sdf: {union: [{sphere: {}}]}\n";
  EXPECT_NE(error_of(yaml, {{"sdf.union.5.sphere.radius", "1"}}).find("past the end"), std::string::npos);
  EXPECT_NE(error_of(yaml, {{"sdf.union.x", "1"}}).find("list index"), std::string::npos);
  EXPECT_NE(error_of(yaml, {{"render..width", "1"}}).find("empty component"), std::string::npos);
  EXPECT_NE(error_of(yaml, {{"render.width", "[1"}}).find("not valid YAML"), std::string::npos);
  EXPECT_NE(error_of(yaml, {{"render.width", "0"}}).find("s.yaml (--set): render.width"), std::string::npos);
  EXPECT_NE(error_of(yaml, {{"sdf.union.-1.sphere.radius", "1"}}).find("'-1' must be a list index"), std::string::npos);
  EXPECT_NE(
      error_of(yaml, {{"lights.0.point.intensity", "2"}}).find("the scene has no lights, so index 0 reaches nothing"),
      std::string::npos);
  // An override that adds a second node kind is blamed on --set, not on the file's line.
  EXPECT_EQ(
      error_of(yaml, {{"sdf.sphere.radius", "1"}}),
      "s.yaml (--set): sdf must be a map with one key naming the node kind, e.g. sphere: {radius: 1} (got 2 keys: "
      "union, sphere)");
}

TEST(SceneLoader, OverridesReplaceListItemsAndFillAnEmptyFile) {
  const Scene item =
      load_scene_text("sdf: {union: [{sphere: {}}]}\n", "s.yaml", {{"sdf.union.0", "{box: {half_size: [1, 2, 3]}}"}});
  ASSERT_EQ(item.sdf.children.size(), 1u);
  EXPECT_EQ(std::get<Box>(item.sdf.children[0].params).half_size, glm::dvec3(1, 2, 3));
  const Scene empty = load_scene_text("", "s.yaml", {{"sdf", "{torus: {major_radius: 2}}"}});
  EXPECT_EQ(std::get<Torus>(empty.sdf.params).major_radius, 2.0);
  EXPECT_EQ(error_of("sdf: {sphere: {}}\nrender: {width: 32}\n", {{"render.width.x", "1"}}),
            "--set render.width.x=1: 'width' is a value, not a map or list");
}

TEST(SceneLoader, RejectsBadOperatorShapesAndVectors) {
  EXPECT_EQ(error_of("sdf: {repeat: {period: [0, 0, 0], children: [{sphere: {}}]}}\n"),
            "s.yaml:1:24: sdf.repeat.period must repeat along at least one axis (a component > 0)");
  EXPECT_EQ(error_of("sdf: {union: 5}\n"),
            "s.yaml:1:14: sdf.union must be a list of nodes or a map with children (got '5')");
  EXPECT_EQ(error_of("sdf: {repeat: {period: [1, 1, 1], children: [{sphere: {}}, {box: {}}]}}\n"),
            "s.yaml:1:45: sdf.repeat takes exactly 1 child node (got 2); wrap several in a union");
  EXPECT_EQ(error_of("sdf: {displace: {amplitude: 0.1, children: []}}\n"),
            "s.yaml:1:44: sdf.displace needs at least 1 child node (got 0)");
  EXPECT_EQ(error_of("sdf: {sphere: {center: [1, 2]}}\n"),
            "s.yaml:1:24: sdf.sphere.center must be a list of 3 numbers [x, y, z] (got 2 items)");
}

// The catalogue's kinds (issue 25): each bad value is named with its place in the file.
TEST(SceneLoader, RejectsBadCatalogueValues) {
  const auto expect_error = [](const std::string& yaml, const std::string& location, const std::string& says) {
    const std::string error = error_of(yaml);
    EXPECT_EQ(error.rfind(location, 0), 0u) << error;
    EXPECT_NE(error.find(says), std::string::npos) << error;
  };
  expect_error("sdf: {octahedron: {size: 0}}\n", "s.yaml:1:26: ", "sdf.octahedron.size");
  expect_error("sdf: {hex_prism: {radius: -1}}\n", "s.yaml:1:27: ", "sdf.hex_prism.radius");
  expect_error("sdf: {capped_cone: {bottom_radius: 0, top_radius: 0}}\n", "s.yaml:1:20: ", "must not both be 0");
  expect_error("sdf: {ellipsoid: {radii: [1, 0, 1]}}\n", "s.yaml:1:", "sdf.ellipsoid.radii");
  expect_error("sdf: {ellipsoid: {radii: [1, .nan, 1]}}\n", "s.yaml:1:", "sdf.ellipsoid.radii");
  expect_error("sdf: {elongate: {h: [1, -1, 0], children: [{sphere: {}}]}}\n", "s.yaml:1:", "sdf.elongate.h");
  expect_error("sdf: {elongate: {children: [{sphere: {}}]}}\n", "s.yaml:1:", "h");
  expect_error("sdf: {onion: {thickness: 0, children: [{sphere: {}}]}}\n", "s.yaml:1:26: ", "sdf.onion.thickness");
  expect_error("sdf: {round: {radius: 0.1, children: []}}\n", "s.yaml:1:", "needs at least 1 child");
  expect_error("sdf: {mirror: {axes: [w], children: [{sphere: {}}]}}\n", "s.yaml:1:23: ", "unknown axis 'w'");
  expect_error("sdf: {mirror: {axes: [x, x], children: [{sphere: {}}]}}\n", "s.yaml:1:26: ", "axis x is listed twice");
  expect_error("sdf: {mirror: {axes: [], children: [{sphere: {}}]}}\n", "s.yaml:1:22: ", "non-empty list");
  expect_error("sdf: {repeat_polar: {count: 0, children: [{sphere: {}}]}}\n",
               "s.yaml:1:29: ", "sdf.repeat_polar.count");
  expect_error("sdf: {repeat_polar: {count: 2.5, children: [{sphere: {}}]}}\n",
               "s.yaml:1:29: ", "sdf.repeat_polar.count");
  expect_error("sdf: {repeat_limited: {period: [1, 0, 0], min: [1, 0, 0], max: [0, 0, 0], children: [{sphere: {}}]}}\n",
               "s.yaml:1:", "sdf.repeat_limited.min[0] must be at most sdf.repeat_limited.max[0] (got 1 > 0)");
  expect_error("sdf: {repeat_limited: {period: [1, 0, 0], min: [0, 0], max: [0, 0, 0], children: [{sphere: {}}]}}\n",
               "s.yaml:1:", "list of 3 integers");
  expect_error("sdf: {repeat_limited: {period: [0, 0, 0], min: [0, 0, 0], max: [0, 0, 0], children: [{sphere: {}}]}}\n",
               "s.yaml:1:", "must repeat along at least one axis");
}

// Integers are decimal, as YAML 1.2 reads them: yaml-cpp alone took 0640 for octal 416 and 0x40
// for 64, silently.
TEST(SceneLoader, IntegersAreDecimal) {
  EXPECT_EQ(scene_from_yaml("sdf: {sphere: {}}\nrender: {max_steps: 0640, width: +32}\n").render.max_steps, 640);
  EXPECT_EQ(scene_from_yaml("sdf: {sphere: {}}\nrender: {max_steps: 0640, width: +32}\n").render.width, 32);
  EXPECT_EQ(error_of("sdf: {sphere: {}}\nrender: {max_steps: 0x40}\n"),
            "s.yaml:2:21: render.max_steps must be an integer in decimal digits (got '0x40')");
  EXPECT_EQ(error_of("sdf: {sphere: {}}\nrender: {max_steps: 99999999999999999999}\n"),
            "s.yaml:2:21: render.max_steps must be in [1, 1000000] (got 99999999999999999999)");
}

// yaml-cpp marks an empty value where the next token starts (`camera:` then `sdf:`: line 2, under
// sdf); the message names the key's place. A value from --set keeps saying so.
TEST(SceneLoader, AnEmptyValueIsPlacedAtItsKey) {
  EXPECT_EQ(error_of("camera:\nsdf: {sphere: {}}\n"), "s.yaml:1:1: camera must be a map (got nothing)");
  EXPECT_EQ(error_of("sdf: {sphere: {}}\nrender:\n  width: 8\n  epsilon: # later\n\n  height: 4\n"),
            "s.yaml:4:3: render.epsilon must be a number (got nothing)");
  EXPECT_EQ(error_of("sdf: {sphere: {radius: }}\n"), "s.yaml:1:16: sdf.sphere.radius must be a number (got nothing)");
  EXPECT_EQ(error_of("camera: {fov: 60}\nsdf: {sphere: {}}\n", {{"camera", "{fov: }"}}),
            "s.yaml (--set): camera.fov must be a number (got nothing)");
  // A null from --set removes the key instead (issue 29): the camera's defaults apply.
  EXPECT_EQ(error_of("camera: {fov: 60}\nsdf: {sphere: {}}\n", {{"camera", "null"}}), "no error");
  // An empty item of a block list is placed at the list's start (the next token is under another
  // key); in a flow list, at the comma after it.
  EXPECT_EQ(error_of("sdf:\n  union:\n    - sphere: {}\n    -\n\nrender: {width: 8}\n"),
            "s.yaml:3:5: sdf.union[1] must be a map with one key naming the node kind, e.g. sphere: {radius: 1} (got "
            "nothing)");
  EXPECT_EQ(error_of("sdf: {sphere: {center: [1, , 2]}}\n"),
            "s.yaml:1:28: sdf.sphere.center[1] must be a number (got nothing)");
  // Aliases can make the tree a graph with a cycle; the search for the key goes around it.
  EXPECT_EQ(error_of("render: {width: }\nsdf: {sphere: {}}\nlights: &a [{point: {position: [0, 1, 0]}}, *a]\n"),
            "s.yaml:1:10: render.width must be an integer in decimal digits (got nothing)");
}

TEST(SceneLoader, RejectsBadScenes) {
  EXPECT_NE(error_of("").find("the scene is empty"), std::string::npos);
  EXPECT_NE(error_of("[1, 2]").find("the scene must be a map"), std::string::npos);
  EXPECT_NE(error_of("description: [1]\nsdf: {sphere: {}}\n").find("description must be text"), std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}, box: {}}\n").find("one key naming the node kind"), std::string::npos);
  EXPECT_NE(error_of("sdf: {subtraction: [{sphere: {}}]}\n").find("at least 2 child nodes"), std::string::npos);
  EXPECT_NE(error_of("sdf: {capsule: {a: [0, 0, 0], b: [0, 0, 0]}}\n").find("must differ"), std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}}\nrender: {width: 65536, height: 65536}\n").find("exceeds"), std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}}\ncamera: {position: [1, 1, 1], look_at: [1, 1, 1]}\n").find("must differ"),
            std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}}\ncamera: {fov: 180}\n").find("camera.fov must be in (0, 180)"),
            std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}}\nshading: {model: toon}\n").find("lambert, phong, blinn_phong"),
            std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}}\nlights: [{lamp: {}}]\n").find("unknown key 'lamp'"), std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {}}\nlights: [{spot: {}}]\n").find("lights[0].spot.direction"), std::string::npos);
  EXPECT_NE(error_of("sdf: {sphere: {color: [1, -1, 0]}}\n").find("must be >= 0"), std::string::npos);
}

TEST(SceneLoader, NumbersMayBeExpressionsOfTime) {
  const std::string yaml = "sdf: {sphere: {center: [cos(t), sin(t), 0], radius: \"1 + 0.5 * sin(pi * t)\"}}\n";
  const Scene at_zero = load_scene_text(yaml, "s.yaml", {}, 0.0);
  EXPECT_EQ(std::get<Sphere>(at_zero.sdf.params).center, glm::dvec3(1, 0, 0));
  EXPECT_DOUBLE_EQ(std::get<Sphere>(at_zero.sdf.params).radius, 1.0);
  const Scene at_half = load_scene_text(yaml, "s.yaml", {}, 0.5);
  EXPECT_NEAR(std::get<Sphere>(at_half.sdf.params).center.y, std::sin(0.5), 1e-15);
  EXPECT_DOUBLE_EQ(std::get<Sphere>(at_half.sdf.params).radius, 1.5);
  EXPECT_EQ(at_half.time, 0.5);
  // Ranges apply to the value at that time, which the message shows with the time, and a bad
  // expression names itself.
  EXPECT_NE(
      error_of("sdf: {sphere: {radius: \"sin(t) - 1\"}}\n").find("radius must be > 0 (got sin(t) - 1 = -1 at t = 0)"),
      std::string::npos);
  try {
    load_scene_text("sdf: {sphere: {radius: \"1 / (2 - t)\"}}\n", "s.yaml", {}, 2.0);
    ADD_FAILURE() << "1 / 0 must be refused";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "s.yaml:1:24: sdf.sphere.radius must be finite (got 1 / (2 - t) = inf at t = 2)");
  }
  EXPECT_NE(error_of("sdf: {sphere: {radius: \"cos(\"}}\n").find("expression of the time t"), std::string::npos);
}

TEST(SceneLoader, LimitsTreeDepth) {
  std::string deep = "sdf: ";
  for (int i = 0; i < kMaxTreeDepth; ++i) deep += "{union: [";
  deep += "{sphere: {}}";
  for (int i = 0; i < kMaxTreeDepth; ++i) deep += "]}";
  EXPECT_NE(error_of(deep + "\n").find("deeper than 64 levels"), std::string::npos);
}

}  // namespace
}  // namespace clmarch

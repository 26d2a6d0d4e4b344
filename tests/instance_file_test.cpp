// Instance files (instances: {file, primitive}): one primitive a CSV row, and every way a row or the
// file can be wrong, each a one-line error naming the file and line.
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace clmarch {
namespace {

using testing::TempDir;

/// Writes scene.yaml referring to atoms.csv (with text csv) in dir; returns the scene's path.
std::string write_instance_scene(const TempDir& dir, const std::string& csv, const std::string& primitive = "sphere") {
  std::ofstream(dir / "atoms.csv") << csv;
  const std::filesystem::path scene = dir / "scene.yaml";
  std::ofstream(scene) << "sdf:\n  smooth_union:\n    k: 0.1\n    children:\n      - sphere: {radius: 0.5}\n"
                       << "      - instances: {file: atoms.csv, primitive: " << primitive << "}\n";
  return scene.string();
}

std::string error_loading(const std::string& path) {
  try {
    load_scene_file(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InstanceFile, EachRowIsAChildInTheFilesOrder) {
  TempDir dir;
  const std::string path = write_instance_scene(dir,
                                                "# atoms\ncenter_x,center_y,center_z,radius,color_r,color_g,color_b\n"
                                                "1,2,3,0.5,1,0,0\n\n-1, 0, 0.25 ,1.5,0,0,1\n");
  const Scene scene = load_scene_file(path);
  ASSERT_EQ(scene.sdf.children.size(), 3u);
  const Sphere& second = std::get<Sphere>(scene.sdf.children[2].params);
  EXPECT_EQ(second.center, glm::dvec3(-1, 0, 0.25));
  EXPECT_EQ(second.radius, 1.5);
  EXPECT_EQ(*scene.sdf.children[1].color, glm::dvec3(1, 0, 0));
  EXPECT_EQ(std::get<Sphere>(scene.sdf.children[1].params).center, glm::dvec3(1, 2, 3));
}

TEST(InstanceFile, OtherPrimitivesAndTheirKeys) {
  TempDir dir;
  const std::string path = write_instance_scene(
      dir, "half_size_x,half_size_y,half_size_z,translate_x,translate_y,translate_z\n1,2,3,0,1,0\n", "box");
  const Scene scene = load_scene_file(path);
  EXPECT_EQ(std::get<Box>(scene.sdf.children[1].params).half_size, glm::dvec3(1, 2, 3));
  EXPECT_EQ(scene.sdf.children[1].transform.translate, glm::dvec3(0, 1, 0));
}

TEST(InstanceFile, BadRowsNameTheFileAndLine) {
  TempDir dir;
  const std::string csv = (dir / "atoms.csv").string();
  EXPECT_EQ(error_loading(write_instance_scene(dir, "radius\n1\n-1\n")),
            csv + ":3: sdf.smooth_union[1].instances[1].sphere.radius must be > 0 (got -1)");
  EXPECT_EQ(error_loading(write_instance_scene(dir, "center_x,center_y,center_z,radius\n0,0,0,1\n0,x,0,1\n")),
            csv + ":3:3: center_y must be a finite number (got 'x')");
  EXPECT_EQ(error_loading(write_instance_scene(dir, "radius\n1\nnan\n")),
            csv + ":3:1: radius must be a finite number (got 'nan')");
  EXPECT_EQ(error_loading(write_instance_scene(dir, "center_x,radius\n1,1,1\n"))
                .find(csv + ":2: the row has 3 values (expected 2"),
            0u);
  EXPECT_EQ(error_loading(write_instance_scene(dir, "center_x,radius\n1,1\n"))
                .find(csv + ":1: column center needs its companions"),
            0u);
  EXPECT_EQ(error_loading(write_instance_scene(dir, "radius,radius\n1,1\n")),
            csv + ":1:8: column 'radius' appears twice in the header row");
  EXPECT_NE(error_loading(write_instance_scene(dir, "radius,colour_r,colour_g,colour_b\n1,1,1,1\n")).find(csv + ":2: "),
            std::string::npos);
  EXPECT_NE(error_loading(write_instance_scene(dir, "radius,colour_r,colour_g,colour_b\n1,1,1,1\n")).find("colour"),
            std::string::npos);
  EXPECT_EQ(error_loading(write_instance_scene(dir, "")),
            csv + ": the instance file is empty (it needs a header row of column names)");
}

TEST(InstanceFile, BadKeysNameTheSceneFile) {
  TempDir dir;
  const std::string scene = (dir / "scene.yaml").string();
  EXPECT_EQ(error_loading(write_instance_scene(dir, "radius\n1\n", "union"))
                .find(scene + ":6:49: sdf.smooth_union[1].instances.primitive: 'union' is not a primitive"),
            0u)
      << error_loading(write_instance_scene(dir, "radius\n1\n", "union"));
  std::ofstream(scene) << "sdf:\n  union:\n    - instances: {file: missing.csv, primitive: sphere}\n";
  EXPECT_EQ(error_loading(scene).find(scene + ":3:25: sdf.union[0].instances.file: cannot read the instance file"), 0u)
      << error_loading(scene);
  std::ofstream(scene) << "sdf:\n  union:\n    - instances: {file: atoms.csv}\n";
  EXPECT_NE(error_loading(scene).find("primitive"), std::string::npos) << error_loading(scene);
}

TEST(InstanceFile, TooManyRowsFailBeforeTheyAreBuilt) {
  TempDir dir;
  {
    std::ofstream csv(dir / "atoms.csv");
    csv << "radius\n";
    for (int i = 0; i <= kMaxTreeNodes; ++i) csv << "1\n";
  }
  std::ofstream(dir / "scene.yaml") << "sdf:\n  union:\n    - instances: {file: atoms.csv, primitive: sphere}\n";
  const std::string message = error_loading((dir / "scene.yaml").string());
  EXPECT_NE(message.find("too many rows (expected at most 1999999)"), std::string::npos) << message;
}

TEST(InstanceFile, ABadRowFailsARenderWithNoImage) {
  TempDir dir;
  const std::string scene = write_instance_scene(dir, "radius\n1\n0\n");
  const testing::CommandResult result = testing::run_clmarch({"render", scene, "-o", (dir / "out.png").string()});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.err.find("atoms.csv:3: "), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

}  // namespace
}  // namespace clmarch

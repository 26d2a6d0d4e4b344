// The loader's size limits against hostile or runaway input: YAML alias bombs ("billion laughs"),
// aliases that make cycles, huge lists and files, and --set values that do the same. Each must
// fail with one positioned line, after a bounded amount of work.
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace clmarch {
namespace {

using testing::error_of;

/// An SDF tree of 10^levels spheres in a few lines: each level is a union of ten aliases of the
/// level below ("billion laughs" with levels = 9).
std::string alias_bomb(int levels) {
  std::string yaml = "sdf:\n  union:\n    - &l0 {sphere: {}}\n";
  for (int level = 1; level <= levels; ++level) {
    yaml += "    - &l" + std::to_string(level) + " {union: [";
    for (int k = 0; k < 10; ++k) yaml += (k ? ", *l" : "*l") + std::to_string(level - 1);
    yaml += "]}\n";
  }
  return yaml;
}

TEST(SceneLimits, AliasBombStopsAtTheNodeLimit) {
  // 10^9 nodes if expanded; the walk must stop at the 10001st node reached through an alias, inside
  // the expansion of level 4 (the list item on line 7). An aliased node is the anchored one, so the
  // position is its anchor's (line 3, the spheres of level 0) and the path says how the walk got there.
  const std::string message = error_of(alias_bomb(9));
  EXPECT_EQ(message.find("s.yaml:3:7: sdf.union[4].union[7]"), 0u) << message;
  EXPECT_NE(
      message.find("the tree has too many nodes through aliases (got aliased node 10001 here, expected at most 10000"),
      std::string::npos)
      << message;
}

TEST(SceneLimits, TreesUpToTheNodeLimitLoad) {
  // 1 + 11 + 111 + 1111 = 1234 nodes with level 3, plus the root: well inside the limit.
  const Scene scene = load_scene_text(alias_bomb(3), "s.yaml");
  EXPECT_EQ(scene.sdf.children.size(), 4u);
  // Nodes written out, not aliased, count only against the tree's limit (kMaxTreeNodes, tested with
  // instance files in instance_file_test.cpp).
  std::string flat = "sdf:\n  union:\n";
  for (int i = 0; i < 3 * kMaxAliasedNodes; ++i) flat += "    - sphere: {}\n";
  EXPECT_EQ(load_scene_text(flat, "s.yaml").sdf.children.size(), static_cast<std::size_t>(3 * kMaxAliasedNodes));
}

TEST(SceneLimits, AliasCycleIsTooDeep) {
  // yaml-cpp registers an anchor before reading its contents, so *a inside &a is the map itself.
  const std::string message = error_of("sdf: &a {union: [*a]}\n");
  EXPECT_NE(message.find("s.yaml:1:6: "), std::string::npos) << message;
  EXPECT_NE(message.find("deeper than 64 levels (got level 65, expected at most 64"), std::string::npos) << message;
}

TEST(SceneLimits, HugeListsFailBeforeTheyAreBuilt) {
  std::string lights = "sdf: {sphere: {}}\nlights: [";
  for (int i = 0; i <= kMaxLights; ++i) lights += "{directional: {direction: [0, 1, 0]}}, ";
  lights += "]\n";
  EXPECT_NE(error_of(lights).find("s.yaml:2:9: lights has too many entries (got 1025, expected at most 1024)"),
            std::string::npos)
      << error_of(lights);
  // Three million lights: the counting parse stops at value 2500001, long before the list is built.
  std::string million = "sdf: {sphere: {}}\nlights: [";
  for (int i = 0; i < 3000000; ++i) million += "0,";
  million += "]\n";
  const std::string message = error_of(million);
  EXPECT_NE(message.find("s.yaml:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("too many YAML values (got value 2500001 here, expected at most 2500000)"), std::string::npos)
      << message;
}

TEST(SceneLimits, SetValuesAreBoundedToo) {
  const std::string yaml = "sdf: {sphere: {}}\n";
  // The override's value is copied with its aliases expanded: 10^9 scalars if nothing stopped it.
  std::string bomb = "[&a [0,0,0,0,0,0,0,0,0,0]";
  for (char name = 'b'; name <= 'j'; ++name) {
    bomb += std::string(", &") + name + " [";
    for (int k = 0; k < 10; ++k) bomb += std::string(k ? ", *" : "*") + static_cast<char>(name - 1);
    bomb += "]";
  }
  bomb += "]";
  const std::string too_many = error_of(yaml, {{"render.width", bomb}});
  EXPECT_NE(too_many.find("--set render.width="), std::string::npos) << too_many;
  EXPECT_NE(too_many.find("too many YAML values (got value 100001, expected at most 100000"), std::string::npos)
      << too_many;
  const std::string cycle = error_of(yaml, {{"sdf", "&a {union: [*a]}"}});
  EXPECT_NE(cycle.find("--set sdf=&a {union: [*a]}: the value nests too deep (got level 1001, expected at most 1000)"),
            std::string::npos)
      << cycle;
  // Messages stay on one line whatever the value holds.
  const std::string multi_line = error_of(yaml, {{"render.width", "[1,\n2"}});
  EXPECT_EQ(multi_line.find('\n'), std::string::npos) << multi_line;
}

TEST(SceneLimits, HugeFilesAreNotRead) {
  testing::TempDir dir;
  const std::filesystem::path big = dir / "big.yaml";
  std::ofstream(big) << "sdf: {sphere: {}}\n";
  // A sparse file: no disk space, but reading it would cost 80 MiB of memory and a long parse.
  std::filesystem::resize_file(big, 80 << 20);
  try {
    load_scene_file(big.string());
    FAIL() << "an 80 MiB scene file loaded";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              big.string() + ": the scene file is too large (got more than 67108864 bytes, expected at most 67108864)");
  }
  try {
    load_scene_file(dir.path().string());
    FAIL() << "a folder loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
}

TEST(SceneLimits, DeepYamlNestingIsRefusedNotACrash) {
  // yaml-cpp's parser refuses nesting deeper than its own guard (saying "bad file"); the scene
  // never gets that far.
  const std::string deep = "sdf: " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  const std::string message = error_of(deep);
  EXPECT_EQ(message.find("s.yaml:1:"), 0u) << message;
  EXPECT_NE(message.find(": the YAML is nested more than 500 levels deep (an sdf tree may have 64)"), std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace clmarch

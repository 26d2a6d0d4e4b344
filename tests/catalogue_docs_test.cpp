// docs/catalogue.md (written by scripts/catalogue.sh) shows every node kind of
// scene/node_kinds.def with its picture, and the picture is there.
#include "scene/scene.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <string>

namespace clmarch {
namespace {

TEST(CatalogueDocs, EveryKindHasItsPicture) {
  const std::string page = testing::read_text(testing::source_path("docs/catalogue.md"));
  for (NodeKind kind : kAllNodeKinds) {
    const std::string name(node_kind_name(kind));
    const std::string picture = fmt::format("images/catalogue/{}.png", name);
    EXPECT_NE(page.find(fmt::format("| ![{}]({}) | `{}` |", name, picture, name)), std::string::npos)
        << "docs/catalogue.md has no row for " << name << ": add it to scripts/catalogue.sh and run it";
    EXPECT_TRUE(std::filesystem::exists(testing::source_path("docs/" + picture))) << picture;
  }
}

}  // namespace
}  // namespace clmarch

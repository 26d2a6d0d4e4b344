// docs/scene-format.md lists every node kind of scene/node_kinds.def in a table row of its own,
// with every parameter of its declaration, and the defaults and status the declaration gives.
#include "scene/glsl_node_reader.hpp"
#include "scene/scene.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <sstream>
#include <string>

namespace clmarch {
namespace {

using testing::read_text;
using testing::source_path;

/// The table rows of docs/scene-format.md that start with the kind's name (its parameter row,
/// and others such as the step-factor table's), joined; "" if none.
std::string docs_row(const std::string& page, std::string_view kind) {
  std::istringstream lines(page);
  const std::string start = fmt::format("| `{}` |", kind);
  std::string rows;
  for (std::string line; std::getline(lines, line);) {
    if (line.starts_with(start)) rows += line + "\n";
  }
  return rows;
}

TEST(KindDocs, EveryKindHasARowNamingItsParameters) {
  const std::string page = read_text(source_path("docs/scene-format.md"));
  for (NodeKind kind : kAllNodeKinds) {
    SCOPED_TRACE(std::string(node_kind_name(kind)));
    const std::string row = docs_row(page, node_kind_name(kind));
    ASSERT_FALSE(row.empty()) << "docs/scene-format.md has no table row | `" << node_kind_name(kind) << "` |";
    for (const ParamSpec& spec : param_table(kind)) {
      // A program is read from keys of its own.
      if (spec.type == ParamType::Program) {
        for (std::string_view key : kGlslNodeKeys) {
          EXPECT_NE(row.find(fmt::format("`{}`", key)), std::string::npos) << "its row does not name `" << key << "`";
        }
        continue;
      }
      EXPECT_NE(row.find(fmt::format("`{}`", spec.key)), std::string::npos)
          << "its row does not name `" << spec.key << "`";
      for (const char* choice : spec.choices) {
        EXPECT_NE(row.find(fmt::format("`{}`", choice)), std::string::npos)
            << "its row does not name the choice `" << choice << "`";
      }
    }
  }
}

TEST(KindDocs, PrimitivesThatAreNotExactSaySo) {
  const std::string page = read_text(source_path("docs/scene-format.md"));
  for (NodeKind kind : kAllNodeKinds) {
    if (!is_primitive(kind) || field_quality(kind) == FieldQuality::Exact) continue;
    SCOPED_TRACE(std::string(node_kind_name(kind)));
    EXPECT_NE(docs_row(page, node_kind_name(kind)).find("bound"), std::string::npos)
        << "a primitive that is not exact needs its status (bound, estimate) in its row";
  }
}

// A blend's status in its row follows operator_lipschitz: "estimate" where it can be steeper than 1.
TEST(KindDocs, BlendsSayWhetherTheyAreBoundsOrEstimates) {
  const std::string page = read_text(source_path("docs/scene-format.md"));
  for (NodeKind kind : kAllNodeKinds) {
    if (!is_blend_operator(kind)) continue;
    SCOPED_TRACE(std::string(node_kind_name(kind)));
    Node node = node_of_kind(kind);
    node.children = {node_of_kind(NodeKind::Sphere), node_of_kind(NodeKind::Sphere)};
    const std::string row = docs_row(page, node_kind_name(kind));
    const std::string status = operator_lipschitz(node) > 1.0 ? "| estimate |" : "| bound |";
    EXPECT_NE(row.find(status), std::string::npos) << "its row needs the status " << status;
  }
}

}  // namespace
}  // namespace clmarch

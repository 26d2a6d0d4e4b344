// What scene errors offer the user: whole lists of names, only names that are accepted, and the
// hints for habits from shaders (issue 42's papercuts). The messages' places are in
// cli_errors_test.cpp; here what they must not say.
#include "scene/glsl_vectors.hpp"
#include "support/test_support.hpp"

#include <fmt/ranges.h>
#include <gtest/gtest.h>

namespace clmarch {
namespace {

using testing::error_of;

TEST(ErrorHints, AnUnknownKindListsEveryKindUncut) {
  // A long name first, so that the message is past the length where quoted values are cut.
  const std::string message = error_of("sdf:\n  " + std::string(300, 'q') + ": {radius: 1}\n");
  const std::size_t list = message.find("(expected one of: ");
  ASSERT_NE(list, std::string::npos) << message;
  std::vector<std::string_view> names;
  for (NodeKind kind : kAllNodeKinds) names.push_back(node_kind_name(kind));
  EXPECT_EQ(message.substr(list), fmt::format("(expected one of: {})", fmt::join(names, ", ")));
}

TEST(ErrorHints, AColorExpressionOffersOnlyTheFunctionsColorsTake) {
  const std::string message = error_of("sdf:\n  sphere: {color: [\"sinh(x)\", y, 0]}\n");
  EXPECT_NE(message.find("'sinh' is not a function a color expression takes"), std::string::npos) << message;
  EXPECT_NE(message.find("the functions abs, sign, floor"), std::string::npos) << message;
  // muparser's own functions, which numbers take and colours refuse.
  for (const char* refused : {"sinh", "rint", "avg", "log10", "atan2"})
    EXPECT_EQ(message.find(fmt::format(", {}", refused)), std::string::npos) << refused << " offered: " << message;
}

TEST(ErrorHints, TheTimesOtherNamesSuggestT) {
  for (const char* name : {"iTime", "time", "u_time"}) {
    const std::string number = error_of(fmt::format("sdf: {{sphere: {{radius: \"1 + {}\"}}}}\n", name));
    EXPECT_NE(number.find("did you mean t?"), std::string::npos) << number;
    const std::string color = error_of(fmt::format("sdf: {{sphere: {{color: [\"{}\", x, 0]}}}}\n", name));
    EXPECT_NE(color.find("did you mean t?"), std::string::npos) << color;
  }
  const std::string other = error_of("sdf: {sphere: {radius: \"1 + speed\"}}\n");
  EXPECT_EQ(other.find("did you mean"), std::string::npos) << other;
}

TEST(ErrorHints, GlslVectorsBecomeYamlLists) {
  EXPECT_EQ(glsl_vectors_as_yaml("vec3(1, .5, 0)"), "[1, 0.5, 0]");
  EXPECT_EQ(glsl_vectors_as_yaml("ivec2(3,4)"), "[3, 4]");
  EXPECT_EQ(glsl_vectors_as_yaml("vec3(1, 0, 0), vec3(0, 0, 1)"), "[1, 0, 0], [0, 0, 1]");
  EXPECT_EQ(glsl_vectors_as_yaml("vec3(sin(t), 0, 1)"), "") << "a call inside is no plain argument";
  EXPECT_EQ(glsl_vectors_as_yaml("max(0.1, t)"), "");
  EXPECT_TRUE(starts_glsl_vector(" vec4 (1"));
  EXPECT_FALSE(starts_glsl_vector("vector(1"));
}

}  // namespace
}  // namespace clmarch

// --help of each command: every option it lists is used in one of its examples.
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

namespace clmarch {
namespace {

using testing::run_clmarch;

struct HelpText {
  /// Each option's spellings, e.g. {"-o", "--output"}, from the "Options:" list (--help excluded).
  std::vector<std::vector<std::string>> options;
  std::string examples;
};

HelpText parse_help(const std::string& text) {
  HelpText help;
  const std::size_t options = text.find("\nOptions:\n");
  const std::size_t examples = text.find("\nExamples:\n");
  EXPECT_NE(options, std::string::npos) << text;
  EXPECT_NE(examples, std::string::npos) << text;
  if (options == std::string::npos || examples == std::string::npos) return help;
  help.examples = text.substr(examples);
  static const std::regex option_line(R"(^  (-[A-Za-z](?:,--[a-z-]+)?|--[a-z-]+)[ ,])");
  std::istringstream lines(text.substr(options, examples - options));
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (!std::regex_search(line, match, option_line)) continue;
    std::vector<std::string> spellings;
    std::stringstream names(match[1].str());
    for (std::string name; std::getline(names, name, ',');) spellings.push_back(name);
    if (spellings.back() != "--help") help.options.push_back(spellings);
  }
  return help;
}

void expect_every_option_in_an_example(const std::vector<std::string>& command, std::size_t at_least) {
  const auto result = run_clmarch(command);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const HelpText help = parse_help(result.out);
  EXPECT_GE(help.options.size(), at_least) << result.out;
  for (const std::vector<std::string>& spellings : help.options) {
    bool used = false;
    for (const std::string& s : spellings)
      used = used || help.examples.find(" " + s + " ") != std::string::npos ||
             help.examples.find(" " + s + "\n") != std::string::npos;
    EXPECT_TRUE(used) << spellings.back() << " has no example in:\n" << help.examples;
  }
}

TEST(Help, TopLevelShowsGlobalFlagsEveryCommandAndExitCodes) {
  expect_every_option_in_an_example({"--help"}, 2);
  const auto result = run_clmarch({"--help"});
  for (const char* command : {"clmarch render ", "clmarch check ", "clmarch field ", "clmarch devices"}) {
    EXPECT_NE(result.out.find(command), std::string::npos) << command << " has no example:\n" << result.out;
  }
  EXPECT_NE(result.out.find("Exit codes: 0 success"), std::string::npos) << result.out;
}

TEST(Help, VersionPrintsTheProjectsVersion) {
  const auto result = run_clmarch({"--version"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out, std::string("clmarch ") + CLMARCH_VERSION + "\n");
  EXPECT_TRUE(std::regex_match(std::string(CLMARCH_VERSION), std::regex(R"(\d+\.\d+\.\d+)"))) << CLMARCH_VERSION;
}

TEST(Help, RenderExplainsEveryOptionWithAnExample) { expect_every_option_in_an_example({"render", "--help"}, 9); }

TEST(Help, CheckExplainsEveryOptionWithAnExample) { expect_every_option_in_an_example({"check", "--help"}, 6); }

TEST(Help, BenchExplainsEveryOptionWithAnExample) { expect_every_option_in_an_example({"bench", "--help"}, 8); }

TEST(Help, FieldExplainsEveryOptionWithAnExample) { expect_every_option_in_an_example({"field", "--help"}, 7); }

}  // namespace
}  // namespace clmarch

// The man page clmarch-docgen wrote in the build, rendered by groff (groff-base, scripts/setup.sh):
// no warnings, and every command's options with their whole descriptions, against the CLI11 objects.
#include "cli/command_line.hpp"
#include "support/command_line_walk.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <regex>
#include <sstream>

namespace clmarch {
namespace {

using testing::app_and_commands;
using testing::have_program;
using testing::named_options;
using testing::run_shell;
using testing::shell_quote;
using testing::spellings;

const std::string kManPage = std::string(CLMARCH_DOCGEN_DIR) + "/clmarch.1";

/// text with each run of white space made one space.
std::string collapsed(const std::string& text) { return std::regex_replace(text, std::regex(R"(\s+)"), " "); }

/// The page as plain text, a paragraph a line: no bold or underline, lines long enough never to
/// wrap, no hyphenation.
std::string rendered_page() {
  const auto result = run_shell("groff -man -Tutf8 -rLL=4000n -rHY=0 -P-c -P-b -P-o -P-u " + shell_quote(kManPage));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return result.out;
}

/// The text of a section or subsection of the rendered page, from its heading (a line of its own,
/// indented by indent) to the next heading at the same or a shallower indent.
std::string rendered_section(const std::string& page, const std::string& heading, const std::string& indent) {
  const std::size_t start = page.find("\n" + indent + heading + "\n");
  EXPECT_NE(start, std::string::npos) << heading << " not in:\n" << page;
  if (start == std::string::npos) return {};
  std::smatch next;
  const std::string rest = page.substr(start + heading.size() + indent.size() + 2);
  const std::regex heading_line(indent.empty() ? "\n[A-Z]" : "\n(   )?[A-Za-z]");
  return std::regex_search(rest, next, heading_line) ? rest.substr(0, next.position(0)) : rest;
}

TEST(ManPage, RendersWithoutWarnings) {
  if (!have_program("groff")) GTEST_SKIP() << "groff is not installed (groff-base: scripts/setup.sh)";
  const auto result = run_shell("groff -man -Tutf8 -ww -z " + shell_quote(kManPage));
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.err, "");
  if (have_program("man")) {
    // As lintian checks a package's pages.
    const auto man = run_shell("LC_ALL=C.UTF-8 MANROFFSEQ='' MANWIDTH=80 man --warnings -E UTF-8 -l -Tutf8 -Z " +
                               shell_quote(kManPage) + " >/dev/null");
    EXPECT_EQ(man.exit_code, 0);
    EXPECT_EQ(man.err, "");
  }
}

TEST(ManPage, WritesEveryDashAsAMinusSign) {
  // groff 1.23 and mandoc render a bare '-' as a hyphen (U+2010), which a shell does not take for
  // the '-' of an option (Debian's groff 1.22 maps it back; the page must not count on that).
  const std::string page = testing::read_text(kManPage);
  ASSERT_FALSE(page.empty());
  std::istringstream lines(page);
  for (std::string line; std::getline(lines, line);) {
    if (line.starts_with(".\\\"")) continue;
    for (std::size_t i = line.find('-'); i != std::string::npos; i = line.find('-', i + 1)) {
      EXPECT_TRUE(i > 0 && line[i - 1] == '\\') << "a bare '-' at " << i << " of: " << line;
    }
    EXPECT_FALSE(line.starts_with("'")) << "a text line read as a request: " << line;
  }
}

TEST(ManPage, ShowsEveryCommandsOptionsWithTheirDescriptions) {
  if (!have_program("groff")) GTEST_SKIP() << "groff is not installed (groff-base: scripts/setup.sh)";
  CommandLine line;
  const std::string page = rendered_page();
  const std::string synopsis = rendered_section(page, "SYNOPSIS", "");
  for (const CLI::App* command : app_and_commands(line.app)) {
    const bool top = command == &line.app;
    SCOPED_TRACE(command->get_name());
    const std::string text =
        collapsed(top ? rendered_section(page, "OPTIONS", "") : rendered_section(page, command->get_name(), "   "));
    if (!top) {
      std::string usage = "clmarch [global options] " + command->get_name() + " ";
      for (const CLI::Option* positional :
           command->get_options([](const CLI::Option* o) { return o->get_positional(); })) {
        for (char c : positional->get_name()) usage.push_back(static_cast<char>(std::toupper(c)));
        usage += " ";
      }
      EXPECT_NE(collapsed(synopsis).find(usage), std::string::npos) << usage << " not in:\n" << synopsis;
      EXPECT_NE(text.find(command->get_description()), std::string::npos) << text;
    }
    for (const CLI::Option* option : command->get_options()) {
      EXPECT_NE(text.find(collapsed(option->get_description())), std::string::npos)
          << option->get_name() << "'s description is not in:\n"
          << text;
      for (const std::string& spelling : spellings(*option)) {
        EXPECT_TRUE(std::regex_search(text, std::regex("(^| )" + spelling + "[ ,]"))) << spelling;
      }
    }
  }
}

TEST(ManPage, HasTheExitCodesExamplesAndSections) {
  if (!have_program("groff")) GTEST_SKIP() << "groff is not installed (groff-base: scripts/setup.sh)";
  const std::string page = rendered_page();
  for (const char* heading :
       {"NAME", "SYNOPSIS", "DESCRIPTION", "OPTIONS", "COMMANDS", "EXIT STATUS", "EXAMPLES", "FILES", "SEE ALSO"}) {
    EXPECT_NE(page.find(std::string("\n") + heading + "\n"), std::string::npos) << heading;
  }
  EXPECT_NE(page.find("clmarch - a sphere tracer of signed distance fields on OpenCL"), std::string::npos);
  const std::string exits = collapsed(rendered_section(page, "EXIT STATUS", ""));
  for (const char* status :
       {"0 success", "2 bad input", "70 internal error", "130 interrupted (Ctrl-C; 143 for SIGTERM)"})
    EXPECT_NE(exits.find(status), std::string::npos) << status << " not in: " << exits;
  const std::string examples = collapsed(rendered_section(page, "EXAMPLES", ""));
  EXPECT_NE(examples.find("clmarch render scenes/torus.yaml writes ./torus.png"), std::string::npos) << examples;
  EXPECT_NE(page.find(std::string(CLMARCH_INSTALLED_SCENES)), std::string::npos) << "FILES names the scenes";
}

}  // namespace
}  // namespace clmarch

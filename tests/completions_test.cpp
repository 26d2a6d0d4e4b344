// The shell completions clmarch-docgen wrote in the build, against the command line's CLI11 objects:
// every option of every command in each file, and each shell completing for real (zsh and fish
// where they are installed: scripts/setup.sh --shells).
#include "cli/command_line.hpp"
#include "support/command_line_walk.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>

namespace clmarch {
namespace {

using testing::app_and_commands;
using testing::docgen_file;
using testing::have_program;
using testing::named_options;
using testing::run_shell;
using testing::shell_quote;
using testing::spellings;
using testing::TempDir;

using Words = std::set<std::string>;

/// The lines of text, without empty ones.
Words lines_of(const std::string& text) {
  Words lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    if (!line.empty()) lines.insert(line);
  }
  return lines;
}

/// The text from begin to the first end after it; empty (and a failure) if begin is missing.
std::string section(const std::string& text, const std::string& begin, const std::string& end) {
  const std::size_t start = text.find(begin);
  EXPECT_NE(start, std::string::npos) << "no '" << begin << "' in:\n" << text;
  if (start == std::string::npos) return {};
  return text.substr(start, text.find(end, start + begin.size()) - start);
}

/// A folder with a scene file and a subfolder, to see files and folders offered.
struct WorkFolder {
  WorkFolder() {
    std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {radius: 1}}\n";
    std::filesystem::create_directory(dir / "frames");
  }
  TempDir dir;
};

/// What the values of option complete to in a WorkFolder: its files, its folder, the values CLI11
/// lists for it ({a,b} or a|b after the type name), or nothing for a value to type.
Words expected_values(const CLI::Option& option) {
  const std::string type = option.get_type_name();
  if (type.starts_with("FILE")) return {"scene.yaml", "frames"};
  if (type.starts_with("DIR")) return {"frames"};
  std::smatch match;
  static const std::regex listed(R"(:\{([^}]*)\}|:([\w.+-]+(?:\|[\w.+-]+)+))");
  if (!std::regex_search(type, match, listed)) return {};
  std::string values = match[1].matched ? match[1].str() : match[2].str();
  std::replace(values.begin(), values.end(), ',', '\n');
  std::replace(values.begin(), values.end(), '|', '\n');
  return lines_of(values);
}

/// COMPREPLY of the bash completion for words (the last one is being completed), run in dir.
Words bash_complete(const std::vector<std::string>& words, const std::filesystem::path& dir = "/") {
  std::string script = "source " + shell_quote(std::string(CLMARCH_DOCGEN_DIR) + "/clmarch.bash") + " && cd " +
                       shell_quote(dir.string()) + " && COMP_WORDS=(";
  for (const std::string& word : words) script += " " + shell_quote(word);
  script += "); COMP_CWORD=" + std::to_string(words.size() - 1) + "; _clmarch; printf '%s\\n' \"${COMPREPLY[@]}\"";
  const auto result = run_shell("bash --norc -c " + shell_quote(script));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
  return lines_of(result.out);
}

/// The matches zsh offers for the command line (ending where tab is pressed), run in dir.
Words zsh_complete(const std::string& line, const std::filesystem::path& dir) {
  const auto result = run_shell("cd " + shell_quote(dir.string()) + " && timeout 20 zsh -f " +
                                shell_quote(testing::source_path("tests/support/zsh_complete.zsh").string()) + " " +
                                shell_quote(CLMARCH_DOCGEN_DIR) + " " + shell_quote(line));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return lines_of(result.out);
}

/// The matches fish offers for the command line, without their descriptions, run in dir.
Words fish_complete(const std::string& line, const std::filesystem::path& dir) {
  const auto result = run_shell(
      "cd " + shell_quote(dir.string()) + " && fish --no-config -c " +
      shell_quote("source " + std::string(CLMARCH_DOCGEN_DIR) + "/clmarch.fish; complete -C " + shell_quote(line)));
  EXPECT_EQ(result.exit_code, 0) << result.err;
  Words matches;
  for (const std::string& match : lines_of(result.out)) matches.insert(match.substr(0, match.find('\t')));
  return matches;
}

Words command_names(const CLI::App& app) {
  Words names;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
    names.insert(command->get_name());
  return names;
}

TEST(CompletionFiles, EveryOptionOfEveryCommandIsInEachFile) {
  CommandLine line;
  const std::string bash = docgen_file("clmarch.bash");
  const std::string zsh = docgen_file("_clmarch");
  const std::string fish = docgen_file("clmarch.fish");
  ASSERT_FALSE(bash.empty() || zsh.empty() || fish.empty()) << "not written in " << CLMARCH_DOCGEN_DIR;
  for (const CLI::App* command : app_and_commands(line.app)) {
    const bool top = command == &line.app;
    const std::string& name = command->get_name();
    std::istringstream words(
        section(section(bash, top ? "    '')\n" : "    " + name + ")\n", "      ;;\n"), "options='", "'\n").substr(9));
    const Words bash_words{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    const std::string zsh_function = section(zsh, top ? "\n_clmarch() {" : "\n_clmarch_" + name + "() {", "\n}\n");
    const std::string fish_condition =
        top ? "-n 'not __fish_seen_subcommand_from " : "-n '__fish_seen_subcommand_from " + name + "'";
    std::vector<std::string> fish_lines;
    for (const std::string& fish_line : lines_of(fish)) {
      if (fish_line.find(fish_condition) != std::string::npos) fish_lines.push_back(fish_line + " ");
    }
    for (const CLI::Option* option : named_options(*command)) {
      const bool takes_value = option->get_items_expected_max() > 0;
      for (const std::string& spelling : spellings(*option)) {
        SCOPED_TRACE(name + " " + spelling);
        EXPECT_TRUE(bash_words.contains(spelling));
        EXPECT_TRUE(
            std::regex_search(zsh_function, std::regex("[')*]" + spelling + (takes_value ? "[=+]" : "") + "\\[")))
            << zsh_function;
        const std::string fish_name =
            spelling.starts_with("--") ? " -l " + spelling.substr(2) + " " : " -s " + spelling.substr(1) + " ";
        const bool in_fish = std::any_of(fish_lines.begin(), fish_lines.end(), [&](const std::string& l) {
          return l.find(fish_name) != std::string::npos &&
                 (l.find(" -r ") != std::string::npos || l.find(" -x ") != std::string::npos) == takes_value;
        });
        EXPECT_TRUE(in_fish) << "no line for it" << (takes_value ? " with a value" : " as a flag");
      }
    }
  }
}

TEST(BashCompletion, IsValidBash) {
  const auto result = run_shell("bash -n " + shell_quote(std::string(CLMARCH_DOCGEN_DIR) + "/clmarch.bash"));
  EXPECT_EQ(result.exit_code, 0) << result.err;
}

TEST(BashCompletion, CompletesCommandsAndOptionPrefixes) {
  CommandLine line;
  EXPECT_EQ(bash_complete({"clmarch", ""}), command_names(line.app));
  EXPECT_EQ(bash_complete({"clmarch", "ch"}), Words{"check"});
  EXPECT_EQ(bash_complete({"clmarch", "render", "--sa"}), Words{"--samples"});
  EXPECT_EQ(bash_complete({"clmarch", "--verbose", "render", "--b"}), (Words{"--backend", "--buffers"}));
  // --option=value reaches the completion as three words.
  EXPECT_EQ(bash_complete({"clmarch", "render", "--backend", "=", "ref"}), Words{"reference"});
  EXPECT_EQ(bash_complete({"clmarch", "render", "--backend", "="}), (Words{"opencl", "reference"}));
}

TEST(BashCompletion, OffersEveryOptionOfEachCommandAndNoOther) {
  CommandLine line;
  Words global;
  for (const CLI::Option* option : named_options(line.app)) {
    for (const std::string& spelling : spellings(*option)) global.insert(spelling);
  }
  for (const CLI::App* command : app_and_commands(line.app)) {
    const bool top = command == &line.app;
    SCOPED_TRACE(command->get_name());
    const Words offered = top ? bash_complete({"clmarch", "-"}) : bash_complete({"clmarch", command->get_name(), "-"});
    Words own;
    for (const CLI::Option* option : named_options(*command)) {
      for (const std::string& spelling : spellings(*option)) own.insert(spelling);
    }
    for (const std::string& spelling : own) EXPECT_TRUE(offered.contains(spelling)) << spelling;
    for (const std::string& spelling : offered) {
      EXPECT_TRUE(own.contains(spelling) || global.contains(spelling)) << spelling << " is no option of it";
    }
    // The global flags may follow a command (CLI11's fallthrough).
    if (!top) {
      EXPECT_TRUE(offered.contains("--quiet") && offered.contains("-v"));
    }
  }
}

TEST(BashCompletion, CompletesEachOptionsValue) {
  CommandLine line;
  const WorkFolder folder;
  EXPECT_EQ(expected_values(*line.render->get_option("--backend")), (Words{"opencl", "reference"}));
  EXPECT_EQ(expected_values(*line.render->get_option("--lanes")), (Words{"1", "4", "8", "16"}));
  for (const CLI::App* command : app_and_commands(line.app)) {
    if (command == &line.app) continue;
    const bool takes_scene = !command->get_options([](const CLI::Option* o) { return o->get_positional(); }).empty();
    for (const CLI::Option* option : named_options(*command)) {
      for (const std::string& spelling : spellings(*option)) {
        SCOPED_TRACE(command->get_name() + " " + spelling + " " + option->get_type_name());
        const Words offered = bash_complete({"clmarch", command->get_name(), spelling, ""}, folder.dir.path());
        if (option->get_items_expected_max() > 0) {
          EXPECT_EQ(offered, expected_values(*option));
        } else {
          // After a flag comes the scene file (or nothing).
          EXPECT_EQ(offered, (takes_scene ? Words{"scene.yaml", "frames"} : Words{}));
        }
      }
    }
  }
}

/// What zsh and fish must both complete, complete(line, dir) giving the matches; fish writes a
/// folder with its '/', zsh without.
void expect_shell_completes(const std::function<Words(const std::string&, const std::filesystem::path&)>& complete,
                            const std::string& folder) {
  CommandLine line;
  const WorkFolder work;
  const std::filesystem::path& dir = work.dir.path();
  EXPECT_EQ(complete("clmarch ", dir), command_names(line.app));
  EXPECT_EQ(complete("clmarch render --sa", dir), Words{"--samples"});
  EXPECT_EQ(complete("clmarch render --backend ", dir), (Words{"opencl", "reference"}));
  EXPECT_EQ(complete("clmarch check --out-dir ", dir), Words{folder});
  EXPECT_EQ(complete("clmarch render ", dir), (Words{"scene.yaml", folder}));
  const Words bench = complete("clmarch bench --", dir);
  for (const CLI::Option* option : named_options(*line.bench)) {
    for (const std::string& spelling : spellings(*option)) {
      if (spelling.starts_with("--")) {
        EXPECT_TRUE(bench.contains(spelling)) << spelling;
      }
    }
  }
}

TEST(ZshCompletion, IsValidZshRegisteredByCompinitAndCompletes) {
  if (!have_program("zsh")) GTEST_SKIP() << "zsh is not installed (scripts/setup.sh --shells)";
  const auto syntax = run_shell("zsh -n " + shell_quote(std::string(CLMARCH_DOCGEN_DIR) + "/_clmarch"));
  EXPECT_EQ(syntax.exit_code, 0) << syntax.err;
  // zsh_complete.zsh loads the file through compinit, which finds it by its #compdef line.
  expect_shell_completes(zsh_complete, "frames");
}

TEST(FishCompletion, IsValidFishAndCompletes) {
  if (!have_program("fish")) GTEST_SKIP() << "fish is not installed (scripts/setup.sh --shells)";
  const auto syntax = run_shell("fish --no-execute " + shell_quote(std::string(CLMARCH_DOCGEN_DIR) + "/clmarch.fish"));
  EXPECT_EQ(syntax.exit_code, 0) << syntax.err;
  expect_shell_completes(fish_complete, "frames/");
}

}  // namespace
}  // namespace clmarch

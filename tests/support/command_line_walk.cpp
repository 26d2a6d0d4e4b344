// The command line's CLI11 objects walked directly, and the files clmarch-docgen wrote.
#include "support/command_line_walk.hpp"

#include "support/test_support.hpp"

namespace clmarch::testing {

std::vector<const CLI::App*> app_and_commands(const CLI::App& app) {
  std::vector<const CLI::App*> all{&app};
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) all.push_back(command);
  return all;
}

std::vector<const CLI::Option*> named_options(const CLI::App& command) {
  return command.get_options([](const CLI::Option* option) { return !option->get_positional(); });
}

std::vector<std::string> spellings(const CLI::Option& option) {
  std::vector<std::string> names;
  for (const std::string& name : option.get_lnames()) names.push_back("--" + name);
  for (const std::string& name : option.get_snames()) names.push_back("-" + name);
  return names;
}

std::string docgen_file(const std::string& name) { return read_text(std::filesystem::path(CLMARCH_DOCGEN_DIR) / name); }

bool have_program(const std::string& name) {
  return run_shell("command -v " + shell_quote(name) + " >/dev/null").exit_code == 0;
}

}  // namespace clmarch::testing

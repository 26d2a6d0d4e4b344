// The command line's CLI11 objects walked directly (not through cli/docgen's model), for the tests
// of the files clmarch-docgen writes, and those files as the build wrote them.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace clmarch::testing {

/// The top level, then each subcommand.
std::vector<const CLI::App*> app_and_commands(const CLI::App& app);

/// The options of command that are not positional arguments.
std::vector<const CLI::Option*> named_options(const CLI::App& command);

/// Every spelling of the option: "--output", "-o".
std::vector<std::string> spellings(const CLI::Option& option);

/// The text of a file clmarch-docgen wrote in the build (build/docgen/NAME); empty if absent.
std::string docgen_file(const std::string& name);

/// Whether a program is on PATH.
bool have_program(const std::string& name);

}  // namespace clmarch::testing

// The command line as plain data for the writers of completions and the man page: each command,
// its options (names, value, values to offer, help text) and what its footer says.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace clmarch::docgen {

/// What a completion offers for an option's value (or a positional argument).
enum class ValueKind { None, Text, File, Directory, Choice };

struct OptionModel {
  /// "--size", "-o"; a positional argument has none.
  std::vector<std::string> long_names;
  std::vector<std::string> short_names;
  /// A positional argument's name, e.g. "scene"; empty for options.
  std::string positional;
  /// The value's name in help: "FILE", "INT"; empty for a flag.
  std::string value_name;
  ValueKind kind = ValueKind::None;
  /// The values CLI11 accepts, where a validator lists them ({a,b} or a|b).
  std::vector<std::string> choices;
  /// The option may be given several times (--set, --sweep).
  bool repeatable = false;
  std::string description;

  /// Every spelling, long names first: "--output", "-o".
  std::vector<std::string> names() const;
  /// The description up to its first example or sentence end, for completion menus.
  std::string summary() const;
};

/// A line of a footer's "Examples:" block.
struct Example {
  std::string command;
  /// What follows "# ", or empty.
  std::string comment;
};

/// An entry of the "Exit codes:" line of the top-level footer.
struct ExitStatus {
  std::string code;
  std::string meaning;
};

struct CommandModel {
  /// "render"; the program's own name for the top level.
  std::string name;
  std::string description;
  std::vector<OptionModel> positionals;
  std::vector<OptionModel> options;
  /// The footer's paragraphs that are neither examples nor exit codes.
  std::vector<std::string> notes;
  std::vector<Example> examples;
};

struct ProgramModel {
  CommandModel program;
  std::string version;
  std::vector<CommandModel> commands;
  /// The global options may also follow a command (CLI11's fallthrough).
  bool global_options_anywhere = false;
  std::vector<ExitStatus> exit_statuses;
  /// The global options that a command's completion offers: those a command does not spell
  /// itself, without --version.
  std::vector<OptionModel> options_after(const CommandModel& command) const;
};

/// Walks app and its subcommands. Throws std::runtime_error when the top-level footer has no
/// "Exit codes:" line or a footer's example line has no command.
ProgramModel describe_program(const CLI::App& app, const std::string& version);

}  // namespace clmarch::docgen

// The fish completion: `complete` lines, the global options before a command, each command's
// options (and the global ones they take) after it.
#include "cli/docgen/writers.hpp"

#include "cli/docgen/text.hpp"

#include <fmt/format.h>

namespace clmarch::docgen {
namespace {

/// text as a single-quoted fish word.
std::string quoted(const std::string& text) { return "'" + backslashed(text, "\\'") + "'"; }

/// A `complete` line for the option when condition holds.
std::string complete_line(const std::string& program, const std::string& condition, const OptionModel& option) {
  std::string line = fmt::format("complete -c {} -n {}", program, quoted(condition));
  for (const std::string& name : option.short_names) line += " -s " + name.substr(1);
  for (const std::string& name : option.long_names) line += " -l " + name.substr(2);
  switch (option.kind) {
    case ValueKind::None:
      break;
    case ValueKind::File:
      line += " -r -F";
      break;
    case ValueKind::Directory:
      line += " -x -a '(__fish_complete_directories (commandline -ct))'";
      break;
    case ValueKind::Choice:
      line += " -x -a " + quoted(joined(option.choices, " "));
      break;
    default:
      // A value to type: no files, nothing offered.
      line += " -x";
      break;
  }
  return line + " -d " + quoted(option.summary()) + "\n";
}

}  // namespace

std::string fish_completion(const ProgramModel& model) {
  const std::string& name = model.program.name;
  std::string out = fmt::format(
      "# fish completion for {0}, written by {0}-docgen from the option definitions of {0} {1}.\n"
      "\n"
      "# No file names unless a line below offers them.\n"
      "complete -c {0} -f\n",
      name, model.version);
  std::vector<std::string> commands;
  for (const CommandModel& command : model.commands) commands.push_back(command.name);
  const std::string before_command = "not __fish_seen_subcommand_from " + joined(commands, " ");
  for (const CommandModel& command : model.commands) {
    out += fmt::format("complete -c {} -n {} -a {} -d {}\n", name, quoted(before_command), command.name,
                       quoted(command.description));
  }
  for (const OptionModel& option : model.program.options) out += complete_line(name, before_command, option);
  for (const CommandModel& command : model.commands) {
    const std::string condition = "__fish_seen_subcommand_from " + command.name;
    out += "\n";
    for (const OptionModel& positional : command.positionals) {
      if (positional.kind == ValueKind::File) out += fmt::format("complete -c {} -n {} -F\n", name, quoted(condition));
    }
    for (const OptionModel& option : command.options) out += complete_line(name, condition, option);
    for (const OptionModel& option : model.options_after(command)) out += complete_line(name, condition, option);
  }
  return out;
}

}  // namespace clmarch::docgen

// The bash completion: a case over the command, then over the word before the cursor (an option
// whose value is being typed), else the command's options, the commands, or files.
#include "cli/docgen/writers.hpp"

#include "cli/docgen/text.hpp"

#include <fmt/format.h>

namespace clmarch::docgen {
namespace {

/// The branch of `case $command`: a `case $prev` for the options' values, the words `-` completes
/// to, and whether the command takes a file.
void write_command_case(std::string& out, const std::string& program, const std::string& pattern,
                        const std::vector<OptionModel>& options, const std::vector<OptionModel>& positionals) {
  std::string values;
  std::vector<std::string> words;
  for (const OptionModel& option : options) {
    const std::vector<std::string> names = option.names();
    words.insert(words.end(), names.begin(), names.end());
    const std::string names_pattern = joined(names, " | ");
    switch (option.kind) {
      case ValueKind::None:
        break;
      case ValueKind::File:
        values += fmt::format("        {}) _{}_files \"$cur\"; return ;;\n", names_pattern, program);
        break;
      case ValueKind::Directory:
        values += fmt::format("        {}) _{}_files \"$cur\" -d; return ;;\n", names_pattern, program);
        break;
      case ValueKind::Choice:
        values += fmt::format("        {}) COMPREPLY=($(compgen -W '{}' -- \"$cur\")); return ;;\n", names_pattern,
                              joined(option.choices, " "));
        break;
      case ValueKind::Text:
        // A value to type (a size, a number, key=value): nothing to offer.
        values += fmt::format("        {}) return ;;\n", names_pattern);
        break;
    }
  }
  out += fmt::format("    {})\n", pattern);
  if (!values.empty()) out += "      case $prev in\n" + values + "      esac\n";
  out += fmt::format("      options='{}'\n", joined(words, " "));
  for (const OptionModel& positional : positionals) {
    if (positional.kind == ValueKind::File) out += "      files=1\n";
  }
  out += "      ;;\n";
}

}  // namespace

std::string bash_completion(const ProgramModel& model) {
  const std::string& name = model.program.name;
  std::vector<std::string> commands;
  for (const CommandModel& command : model.commands) commands.push_back(command.name);
  std::string out = fmt::format(
      "# bash completion for {0}, written by {0}-docgen from the option definitions of {0} {1}.\n"
      "\n"
      "# Files (or with -d folders) starting with $1, one a word even with spaces in them.\n"
      "_{0}_files() {{\n"
      "  local IFS=$'\\n'\n"
      "  compopt -o filenames 2>/dev/null\n"
      "  COMPREPLY=($(compgen \"${{2:--f}}\" -- \"$1\"))\n"
      "}}\n"
      "\n"
      "_{0}() {{\n"
      "  local cur=${{COMP_WORDS[COMP_CWORD]}} prev= command= options= files= i\n"
      "  ((COMP_CWORD > 0)) && prev=${{COMP_WORDS[COMP_CWORD - 1]}}\n"
      "  # --option=value arrives as three words: bash breaks words at '=' (COMP_WORDBREAKS).\n"
      "  [[ $cur == = ]] && cur=\n"
      "  [[ $prev == = ]] && ((COMP_CWORD > 1)) && prev=${{COMP_WORDS[COMP_CWORD - 2]}}\n"
      "  for ((i = 1; i < COMP_CWORD; i++)); do\n"
      "    case ${{COMP_WORDS[i]}} in\n"
      "      {2}) command=${{COMP_WORDS[i]}}; break ;;\n"
      "    esac\n"
      "  done\n"
      "  case $command in\n",
      name, model.version, joined(commands, " | "));
  write_command_case(out, name, "''", model.program.options, model.program.positionals);
  for (const CommandModel& command : model.commands) {
    std::vector<OptionModel> options = command.options;
    const std::vector<OptionModel> globals = model.options_after(command);
    options.insert(options.end(), globals.begin(), globals.end());
    write_command_case(out, name, command.name, options, command.positionals);
  }
  out += fmt::format(
      "  esac\n"
      "  if [[ $cur == -* ]]; then\n"
      "    COMPREPLY=($(compgen -W \"$options\" -- \"$cur\"))\n"
      "  elif [[ -z $command ]]; then\n"
      "    COMPREPLY=($(compgen -W '{1}' -- \"$cur\"))\n"
      "  elif [[ -n $files ]]; then\n"
      "    _{0}_files \"$cur\"\n"
      "  fi\n"
      "}}\n"
      "\n"
      "complete -F _{0} {0}\n",
      name, joined(commands, " "));
  return out;
}

}  // namespace clmarch::docgen

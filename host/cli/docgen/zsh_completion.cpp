// The zsh completion: _arguments specs for the global options and each command's, _describe for
// the commands.
#include "cli/docgen/writers.hpp"

#include "cli/docgen/text.hpp"

#include <fmt/format.h>

namespace clmarch::docgen {
namespace {

/// text inside a single-quoted zsh word.
std::string single_quoted(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out;
}

/// The _arguments action that completes the option's value.
std::string value_action(const OptionModel& option) {
  switch (option.kind) {
    case ValueKind::File:
      return "_files";
    case ValueKind::Directory:
      return "_files -/";
    case ValueKind::Choice:
      return "(" + joined(option.choices, " ") + ")";
    default:
      // A value to type: zsh shows the value's name and offers nothing.
      return "";
  }
}

/// One _arguments spec a spelling: '(-o --output)--output=[summary]:FILE:_files'.
void write_option_specs(std::string& out, const OptionModel& option) {
  const std::vector<std::string> names = option.names();
  // A spelling excludes the others, unless the option may be given again.
  const std::string exclusions = option.repeatable || names.size() < 2 ? "" : "(" + joined(names, " ") + ")";
  const std::string summary = backslashed(option.summary(), "\\[]:");
  for (const std::string& name : names) {
    std::string spec = (option.repeatable ? "*" : "") + exclusions + name;
    if (option.kind != ValueKind::None) spec += name.starts_with("--") ? "=" : "+";
    spec += "[" + summary + "]";
    if (option.kind != ValueKind::None)
      spec += ":" + backslashed(option.value_name, "\\:") + ":" + value_action(option);
    out += fmt::format("    '{}' \\\n", single_quoted(spec));
  }
}

}  // namespace

std::string zsh_completion(const ProgramModel& model) {
  const std::string& name = model.program.name;
  std::string out = fmt::format(
      "#compdef {0}\n"
      "# zsh completion for {0}, written by {0}-docgen from the option definitions of {0} {1}.\n",
      name, model.version);
  for (const CommandModel& command : model.commands) {
    out += fmt::format("\n_{}_{}() {{\n  _arguments -s -S \\\n", name, command.name);
    for (const OptionModel& option : command.options) write_option_specs(out, option);
    for (const OptionModel& option : model.options_after(command)) write_option_specs(out, option);
    for (const OptionModel& positional : command.positionals) {
      out += fmt::format("    ':{}:{}' \\\n", single_quoted(backslashed(positional.positional, "\\:")),
                         single_quoted(value_action(positional)));
    }
    out += "    && return\n}\n";
  }
  out += fmt::format("\n_{}() {{\n  local curcontext=$curcontext state line ret=1\n  _arguments -C -s -S \\\n", name);
  for (const OptionModel& option : model.program.options) write_option_specs(out, option);
  out +=
      "    '1:command:->command' \\\n"
      "    '*::argument:->argument' && ret=0\n"
      "  case $state in\n"
      "    command)\n"
      "      local -a commands=(\n";
  for (const CommandModel& command : model.commands) {
    out += fmt::format("        '{}:{}'\n", command.name, single_quoted(command.description));
  }
  out += fmt::format(
      "      )\n"
      "      _describe -t commands '{0} command' commands && ret=0\n"
      "      ;;\n"
      "    argument)\n"
      "      curcontext=${{curcontext%:*:*}}:{0}-$line[1]:\n"
      "      case $line[1] in\n",
      name);
  for (const CommandModel& command : model.commands) {
    out += fmt::format("        {1}) _{0}_{1} && ret=0 ;;\n", name, command.name);
  }
  out += fmt::format(
      "      esac\n"
      "      ;;\n"
      "  esac\n"
      "  return ret\n"
      "}}\n"
      "\n"
      "# Loaded by compinit from fpath it completes at once; sourced, it registers itself.\n"
      "if [[ $funcstack[1] == _{0} ]]; then\n"
      "  _{0} \"$@\"\n"
      "else\n"
      "  compdef _{0} {0}\n"
      "fi\n",
      name);
  return out;
}

}  // namespace clmarch::docgen

// The command line as plain data: read from the CLI::App objects, and from the footers written for
// --help (their "Examples:" blocks and the "Exit codes:" line).
#include "cli/docgen/command_model.hpp"

#include "cli/docgen/text.hpp"

#include <algorithm>
#include <regex>
#include <stdexcept>

namespace clmarch::docgen {
namespace {

/// The values a validator's description lists: CLI::IsMember's "{a,b}", or "a|b" written by hand.
std::vector<std::string> listed_values(const std::string& description) {
  if (description.size() > 2 && description.front() == '{' && description.back() == '}') {
    return split(description.substr(1, description.size() - 2), ',');
  }
  static const std::regex alternatives(R"(^[\w.+-]+(\|[\w.+-]+)+$)");
  if (std::regex_match(description, alternatives)) return split(description, '|');
  return {};
}

OptionModel describe_option(const CLI::Option& option) {
  OptionModel model;
  for (const std::string& name : option.get_lnames()) model.long_names.push_back("--" + name);
  for (const std::string& name : option.get_snames()) model.short_names.push_back("-" + name);
  if (option.get_positional()) model.positional = option.get_name();
  model.description = option.get_description();
  model.repeatable = option.get_expected_max() > 1;
  if (option.get_items_expected_max() == 0) return model;
  // CLI11 tells the type name and each validator's description as one "TYPE:DESCRIPTION:...".
  const std::vector<std::string> type_parts = split(option.get_type_name(), ':');
  model.value_name = type_parts.empty() ? std::string("VALUE") : type_parts.front();
  for (std::size_t i = 1; i < type_parts.size() && model.choices.empty(); ++i)
    model.choices = listed_values(type_parts[i]);
  if (model.value_name == "FILE") {
    model.kind = ValueKind::File;
  } else if (model.value_name == "DIR") {
    model.kind = ValueKind::Directory;
  } else {
    model.kind = model.choices.empty() ? ValueKind::Text : ValueKind::Choice;
  }
  return model;
}

/// "Exit codes: 0 success, 1 check failed, ..., 130 interrupted (...). See docs/cli.md." with its
/// lines joined: the entries, and what follows the list.
std::vector<ExitStatus> parse_exit_statuses(const std::string& text, std::string& rest) {
  const std::size_t end = text.find(". ");
  const std::string list = text.substr(0, end == std::string::npos ? text.size() : end);
  rest = end == std::string::npos ? std::string() : text.substr(end + 2);
  static const std::regex entry(R"(^(\d+) (.+)$)");
  std::vector<ExitStatus> statuses;
  // An entry's meaning may hold commas too: "130 interrupted (Ctrl-C, ...)" is one entry.
  static const std::regex separator(R"(, (?=\d))");
  for (std::sregex_token_iterator it(list.begin(), list.end(), separator, -1), last; it != last; ++it) {
    std::smatch match;
    const std::string item = it->str();
    if (!std::regex_match(item, match, entry))
      throw std::runtime_error("the footer's \"Exit codes:\" entry '" + item + "' is not 'CODE meaning'");
    statuses.push_back({match[1].str(), trimmed(match[2].str())});
  }
  return statuses;
}

/// Splits a footer into notes, examples and exit statuses (only the top level has those).
void read_footer(const std::string& footer, CommandModel& command, std::vector<ExitStatus>* statuses) {
  const std::vector<std::string> lines = split(footer, '\n');
  std::string paragraph;
  const auto end_paragraph = [&] {
    if (!paragraph.empty()) command.notes.push_back(paragraph);
    paragraph.clear();
  };
  bool in_examples = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line == "Examples:") {
      end_paragraph();
      in_examples = true;
      continue;
    }
    if (in_examples && line.starts_with("  ")) {
      const std::size_t comment = line.find(" # ");
      Example example{trimmed(line.substr(0, comment)), ""};
      if (comment != std::string::npos) example.comment = trimmed(line.substr(comment + 3));
      if (example.command.empty())
        throw std::runtime_error(command.name + ": an example line has no command: '" + line + "'");
      command.examples.push_back(example);
      continue;
    }
    in_examples = false;
    if (statuses && line.starts_with("Exit codes: ")) {
      end_paragraph();
      std::string text = line.substr(std::string("Exit codes: ").size());
      while (text.ends_with(",") && i + 1 < lines.size()) text += " " + lines[++i];
      std::string rest;
      *statuses = parse_exit_statuses(text, rest);
      paragraph = rest;
      continue;
    }
    if (trimmed(line).empty()) {
      end_paragraph();
      continue;
    }
    paragraph += (paragraph.empty() ? "" : " ") + trimmed(line);
  }
  end_paragraph();
}

CommandModel describe_command(const CLI::App& app, std::vector<ExitStatus>* statuses) {
  CommandModel command;
  command.name = app.get_name();
  command.description = app.get_description();
  for (const CLI::Option* option : app.get_options()) {
    OptionModel model = describe_option(*option);
    (model.positional.empty() ? command.options : command.positionals).push_back(model);
  }
  read_footer(app.get_footer(), command, statuses);
  return command;
}

}  // namespace

std::vector<std::string> OptionModel::names() const {
  std::vector<std::string> all = long_names;
  all.insert(all.end(), short_names.begin(), short_names.end());
  return all;
}

std::string OptionModel::summary() const {
  std::string text = description;
  const std::size_t example = text.find("e.g.");
  if (example != std::string::npos) {
    // Cut at the nearest " (", ", " or "; " before it, then before a bracket left open.
    std::size_t cut = 0;
    for (const char* separator : {" (", ", ", "; "}) {
      const std::size_t at = text.rfind(separator, example);
      if (at != std::string::npos) cut = std::max(cut, at);
    }
    text = text.substr(0, cut);
    std::size_t open = std::string::npos;
    int depth = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '(' && depth++ == 0) open = i;
      if (text[i] == ')' && depth > 0) --depth;
    }
    if (depth > 0) text = trimmed(text.substr(0, open));
  }
  text = text.substr(0, text.find(". "));
  while (text.ends_with(".") || text.ends_with(" ")) text.pop_back();
  return text;
}

std::vector<OptionModel> ProgramModel::options_after(const CommandModel& command) const {
  std::vector<OptionModel> globals;
  if (!global_options_anywhere) return globals;
  for (const OptionModel& option : program.options) {
    bool taken = std::find(option.long_names.begin(), option.long_names.end(), "--version") != option.long_names.end();
    for (const OptionModel& own : command.options) {
      for (const std::string& name : own.names()) {
        const std::vector<std::string> names = option.names();
        taken = taken || std::find(names.begin(), names.end(), name) != names.end();
      }
    }
    if (!taken) globals.push_back(option);
  }
  return globals;
}

ProgramModel describe_program(const CLI::App& app, const std::string& version) {
  ProgramModel model;
  model.version = version;
  model.program = describe_command(app, &model.exit_statuses);
  if (model.exit_statuses.empty())
    throw std::runtime_error("the top-level footer has no \"Exit codes: CODE meaning, ...\" line");
  model.global_options_anywhere = app.get_fallthrough();
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; }))
    model.commands.push_back(describe_command(*command, nullptr));
  return model;
}

}  // namespace clmarch::docgen

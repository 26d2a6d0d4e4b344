// The man page, man(7) roff: NAME, SYNOPSIS, DESCRIPTION, OPTIONS, COMMANDS, EXIT STATUS,
// EXAMPLES, FILES, SEE ALSO.
#include "cli/docgen/writers.hpp"

#include "cli/docgen/text.hpp"

#include <fmt/format.h>

#include <cctype>

namespace clmarch::docgen {
namespace {

/// text for a roff text line. '-' is written \- so that it renders as the ASCII hyphen-minus a
/// shell takes (groff makes a plain '-' a hyphen in UTF-8), ' and ` as \(aq and \(ga for the same
/// reason.
std::string roff(const std::string& text) {
  std::string out = text.starts_with(".") ? "\\&" : "";
  for (char c : text) {
    switch (c) {
      case '\\':
        out += "\\e";
        break;
      case '-':
        out += "\\-";
        break;
      case '\'':
        out += "\\(aq";
        break;
      case '`':
        out += "\\(ga";
        break;
      default:
        out.push_back(c);
    }
  }
  return out;
}

std::string bold(const std::string& text) { return "\\fB" + roff(text) + "\\fR"; }
std::string italic(const std::string& text) { return "\\fI" + roff(text) + "\\fR"; }

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

/// The option's tag: "-o, --output FILE", "--backend opencl|reference".
std::string option_tag(const OptionModel& option) {
  std::vector<std::string> names;
  for (const std::string& name : option.short_names) names.push_back(bold(name));
  for (const std::string& name : option.long_names) names.push_back(bold(name));
  std::string tag = joined(names, ", ");
  if (option.kind == ValueKind::Choice) {
    std::vector<std::string> choices;
    for (const std::string& choice : option.choices) choices.push_back(italic(choice));
    tag += " " + joined(choices, "|");
  } else if (option.kind != ValueKind::None) {
    tag += " " + italic(option.value_name);
  }
  return tag;
}

void write_options(std::string& out, const std::vector<OptionModel>& options) {
  for (const OptionModel& option : options) {
    out += ".TP\n" + option_tag(option) + "\n" + roff(option.description);
    out += option.repeatable ? " (may be given more than once)\n" : "\n";
  }
}

void write_examples(std::string& out, const std::vector<Example>& examples) {
  for (const Example& example : examples) {
    if (example.comment.empty()) {
      out += ".PP\n" + bold(example.command) + "\n";
    } else {
      out += ".TP\n" + bold(example.command) + "\n" + roff(example.comment) + "\n";
    }
  }
}

/// "clmarch [global options] render SCENE [options]".
std::string synopsis_line(const std::string& program, const CommandModel& command) {
  std::string line = ".B " + roff(program) + "\n[\\fIglobal options\\fR]\n.B " + roff(command.name) + "\n";
  for (const OptionModel& positional : command.positionals) line += ".I " + roff(upper(positional.positional)) + "\n";
  return line + "[\\fIoptions\\fR]\n";
}

}  // namespace

std::string man_page(const ProgramModel& model, const InstalledPaths& paths) {
  const CommandModel& program = model.program;
  const std::string& name = program.name;
  // "clmarch: a sphere tracer ..." is the App's description; NAME wants what follows the colon.
  std::string summary = program.description;
  if (summary.starts_with(name + ": ")) summary = summary.substr(name.size() + 2);
  std::string out = fmt::format(
      ".\\\" {0}(1), written by {0}-docgen from the option definitions of {0} {1}.\n"
      ".TH {2} 1 \"\" \"{0} {1}\" \"User Commands\"\n"
      ".SH NAME\n{0} \\- {3}\n"
      ".SH SYNOPSIS\n",
      name, model.version, upper(name), roff(summary));
  for (const CommandModel& command : model.commands) out += synopsis_line(name, command) + ".br\n";
  out += fmt::format(".B {}\n.BR \\-\\-help \" | \" \\-\\-version\n", roff(name));

  out += ".SH DESCRIPTION\n" + bold(name) + " is " + roff(summary) + ".\n";
  for (const std::string& note : program.notes) out += ".PP\n" + roff(note) + "\n";
  out += ".SH OPTIONS\n";
  if (model.global_options_anywhere) {
    out += "The global options may stand before or after the command.\n";
  }
  write_options(out, program.options);

  out += ".SH COMMANDS\n";
  for (const CommandModel& command : model.commands) {
    out += ".SS " + roff(command.name) + "\n" + roff(command.description) + ".\n";
    for (const std::string& note : command.notes) out += ".PP\n" + roff(note) + "\n";
    for (const OptionModel& positional : command.positionals) {
      out += ".TP\n" + italic(upper(positional.positional)) + "\n" + roff(positional.description) + "\n";
    }
    write_options(out, command.options);
    if (!command.examples.empty()) {
      out += ".PP\nExamples:\n.RS 4\n";
      write_examples(out, command.examples);
      out += ".RE\n";
    }
  }

  out += ".SH EXIT STATUS\n";
  for (const ExitStatus& status : model.exit_statuses) {
    out += ".TP\n.B " + status.code + "\n" + roff(status.meaning) + "\n";
  }
  out += ".SH EXAMPLES\n";
  write_examples(out, program.examples);
  out += fmt::format(
      ".SH FILES\n"
      ".TP\n{0}\n"
      "The example scenes. The examples above name them scenes/NAME.yaml: copy the folder where you "
      "work (\\fBcp \\-r {2} .\\fR) or give their full path.\n"
      ".TP\n{1}\n"
      "README.md, CHANGELOG.md and LICENSE.\n"
      ".SH SEE ALSO\n"
      ".BR clinfo (1),\n"
      ".BR mpirun (1);\n"
      "the scene format and every option in detail: docs/scene\\-format.md and docs/cli.md of the source.\n",
      italic(paths.scenes), italic(paths.docs), roff(paths.scenes));
  return out;
}

}  // namespace clmarch::docgen

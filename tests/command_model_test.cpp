// The command line's model for clmarch-docgen (cli/docgen/command_model): what it reads from the
// CLI::App objects and their footers, and that a footer it cannot read stops the build.
#include "cli/command_line.hpp"
#include "cli/docgen/command_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace clmarch::docgen {
namespace {

const CommandModel& command_named(const ProgramModel& model, const std::string& name) {
  const auto it = std::find_if(model.commands.begin(), model.commands.end(),
                               [&](const CommandModel& command) { return command.name == name; });
  if (it == model.commands.end()) throw std::runtime_error("no command " + name);
  return *it;
}

const OptionModel& option_named(const CommandModel& command, const std::string& name) {
  for (const OptionModel& option : command.options) {
    const std::vector<std::string> names = option.names();
    if (std::find(names.begin(), names.end(), name) != names.end()) return option;
  }
  throw std::runtime_error(command.name + " has no option " + name);
}

TEST(CommandModel, ReadsCommandsOptionsAndWhatTheirValuesAre) {
  CommandLine line;
  const ProgramModel model = describe_program(line.app, "9.8.7");
  EXPECT_EQ(model.version, "9.8.7");
  EXPECT_EQ(model.program.name, "clmarch");
  std::vector<std::string> names;
  for (const CommandModel& command : model.commands) names.push_back(command.name);
  EXPECT_EQ(names, (std::vector<std::string>{"render", "check", "devices", "bench", "mesh", "field", "preview"}));

  const CommandModel& render = command_named(model, "render");
  ASSERT_EQ(render.positionals.size(), 1u);
  EXPECT_EQ(render.positionals[0].positional, "scene");
  EXPECT_EQ(render.positionals[0].kind, ValueKind::File);
  EXPECT_EQ(option_named(render, "--backend").kind, ValueKind::Choice);
  EXPECT_EQ(option_named(render, "--backend").choices, (std::vector<std::string>{"opencl", "reference"}));
  EXPECT_EQ(option_named(render, "--lanes").choices, (std::vector<std::string>{"1", "4", "8", "16"}));
  EXPECT_EQ(option_named(render, "--lanes").value_name, "INT");
  EXPECT_EQ(option_named(render, "-o").names(), (std::vector<std::string>{"--output", "-o"}));
  EXPECT_EQ(option_named(render, "-o").kind, ValueKind::File);
  EXPECT_EQ(option_named(render, "--size").kind, ValueKind::Text);
  EXPECT_EQ(option_named(render, "--samples").kind, ValueKind::Text) << "a range, not a list of values";
  EXPECT_EQ(option_named(render, "--stats").kind, ValueKind::None);
  EXPECT_TRUE(option_named(render, "--set").repeatable);
  EXPECT_FALSE(option_named(render, "--size").repeatable);
  EXPECT_EQ(option_named(command_named(model, "check"), "--out-dir").kind, ValueKind::Directory);
  EXPECT_EQ(option_named(command_named(model, "bench"), "--csv").kind, ValueKind::File);
  EXPECT_TRUE(command_named(model, "devices").positionals.empty());
  EXPECT_EQ(option_named(command_named(model, "field"), "--points").kind, ValueKind::File);
  EXPECT_EQ(option_named(command_named(model, "field"), "--precision").choices,
            (std::vector<std::string>{"float", "double"}));

  // The global flags may follow a command: its completion offers them, but not --version.
  ASSERT_TRUE(model.global_options_anywhere);
  std::vector<std::string> after;
  for (const OptionModel& option : model.options_after(render)) after.push_back(option.names().front());
  EXPECT_EQ(after, (std::vector<std::string>{"--quiet", "--verbose"}));
}

TEST(CommandModel, ReadsExitCodesExamplesAndNotesFromTheFooters) {
  CommandLine line;
  const ProgramModel model = describe_program(line.app, "1.0.0");
  std::vector<std::string> codes;
  for (const ExitStatus& status : model.exit_statuses) codes.push_back(status.code);
  EXPECT_EQ(codes, (std::vector<std::string>{"0", "1", "2", "3", "4", "70", "130"}));
  EXPECT_EQ(model.exit_statuses.back().meaning, "interrupted (Ctrl-C; 143 for SIGTERM)");
  EXPECT_EQ(model.exit_statuses[4].meaning, "output not written") << "the entry that ends the footer's first line";

  ASSERT_FALSE(model.program.examples.empty());
  EXPECT_EQ(model.program.examples[0].command, "clmarch render scenes/torus.yaml");
  EXPECT_EQ(model.program.examples[0].comment, "writes ./torus.png");
  const std::vector<Example>& render = command_named(model, "render").examples;
  const auto mpi = std::find_if(render.begin(), render.end(),
                                [](const Example& example) { return example.command.starts_with("mpirun"); });
  ASSERT_NE(mpi, render.end());
  EXPECT_EQ(mpi->command, "mpirun -n 4 clmarch render scenes/moving_shapes.yaml --frames 0:47 -o frames/shot_####.png");
  EXPECT_EQ(mpi->comment, "over 4 MPI ranks");
  const std::vector<std::string>& bench_notes = command_named(model, "bench").notes;
  ASSERT_FALSE(bench_notes.empty());
  EXPECT_TRUE(bench_notes[0].starts_with("Kernel times are medians of --repeat runs")) << bench_notes[0];
  EXPECT_NE(bench_notes[0].find("ceiling is the scene's distance function"), std::string::npos)
      << "wrapped lines join with a space: " << bench_notes[0];
}

TEST(CommandModel, RefusesATopLevelFooterItCannotReadExitCodesFrom) {
  CLI::App without{"x: a tool", "x"};
  without.footer("Examples:\n  x run   # runs\n");
  EXPECT_THROW(describe_program(without, "1.0.0"), std::runtime_error);
  CLI::App garbled{"x: a tool", "x"};
  garbled.footer("Exit codes: zero success, 1 failure.\n");
  EXPECT_THROW(describe_program(garbled, "1.0.0"), std::runtime_error);
}

TEST(CommandModel, SummaryStopsBeforeTheFirstExampleOrSecondSentence) {
  const auto summary = [](const std::string& description) {
    OptionModel option;
    option.description = description;
    return option.summary();
  };
  EXPECT_EQ(summary("Image size WxH, overriding render.width/height (e.g. --size 320x180)"),
            "Image size WxH, overriding render.width/height");
  EXPECT_EQ(summary("Scene file (YAML or JSON), e.g. scenes/torus.yaml"), "Scene file (YAML or JSON)");
  EXPECT_EQ(summary("Color image (exr, hdr: float). Default: NAME.png (e.g. -o torus.exr)"),
            "Color image (exr, hdr: float)");
  EXPECT_EQ(summary("Device index (default: first GPU, else first CPU; e.g. --device 0)"), "Device index");
  EXPECT_EQ(summary("Print the figures as one JSON object on stdout"),
            "Print the figures as one JSON object on stdout");
}

}  // namespace
}  // namespace clmarch::docgen

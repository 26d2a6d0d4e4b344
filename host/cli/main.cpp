// clmarch: the command-line entry point. Parses the command, installs the Ctrl-C handlers and
// hands errors to run_reporting_errors, which maps them to exit codes.
#include "cli/command_line.hpp"
#include "cli/devices_command.hpp"
#include "cli/error_report.hpp"
#include "cli/interrupts.hpp"
#include "cli/rank_work.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "common/nearest_name.hpp"
#include "common/progress.hpp"
#include "distributed/mpi_world.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <unistd.h>

namespace {

/// Options a user coming from other renderers tries for one clmarch spells otherwise.
constexpr std::pair<std::string_view, std::string_view> kOptionSynonyms[] = {
    {"width", "size"}, {"height", "size"}, {"resolution", "size"},
    {"res", "size"},   {"out", "output"},  {"spp", "samples"}};

/// " (did you mean '--NAME'?)" for the first --option of the command line that its command does
/// not know, or empty.
std::string option_suggestion(const CLI::App& app, int argc, char** argv) {
  const CLI::App* command = &app;
  std::vector<std::string> words(argv + 1, argv + argc);
  for (const std::string& word : words) {
    const auto named = app.get_subcommands([&](const CLI::App* c) { return c->get_name() == word; });
    if (!named.empty()) {
      command = named.front();
      break;
    }
  }
  std::vector<std::string> names;
  for (const CLI::Option* option : command->get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back(name);
  }
  for (const std::string& word : words) {
    if (!word.starts_with("--")) continue;
    const std::string name =
        word.substr(2, word.find('=') == std::string::npos ? std::string::npos : word.find('=') - 2);
    if (std::find(names.begin(), names.end(), name) != names.end()) continue;
    for (const auto& [synonym, option] : kOptionSynonyms) {
      if (name == synonym && std::find(names.begin(), names.end(), option) != names.end())
        return fmt::format(" (did you mean '--{}'?)", option);
    }
    const std::string nearest = clmarch::nearest_name(name, std::vector<std::string_view>(names.begin(), names.end()));
    return nearest.empty() ? std::string() : fmt::format(" (did you mean '--{}'?)", nearest);
  }
  return {};
}

/// The command line's work: parse, then run the command with its errors reported.
int run_main(int argc, char** argv) {
  using namespace clmarch;
  install_interrupt_handlers();
  CommandLine line;
  CLI::App& app = line.app;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 takes a misspelt command for a stray argument and asks for a subcommand.
    for (int i = 1; i < argc; ++i) {
      const std::string word = argv[i];
      if (word.starts_with("-")) continue;
      const auto commands = app.get_subcommands([&](const CLI::App* command) { return command->get_name() == word; });
      if (commands.empty()) {
        std::cerr << "clmarch: unknown command '" << one_line(word)
                  << "' (expected render, check, bench, mesh, field, preview or devices; see clmarch --help)\n";
        return kExitBadInput;
      }
      break;
    }
    std::cerr << "clmarch: " << one_line(e.what()) << option_suggestion(app, argc, argv) << " (see clmarch --help)\n";
    return kExitBadInput;
  }
  set_verbosity(line.quiet ? Verbosity::Quiet : line.verbose ? Verbosity::Verbose : Verbosity::Normal);
  // Under mpirun with several ranks, render and devices share the work out (docs/cli.md#mpi);
  // the other commands run whole on every rank. A plain run never starts MPI.
  if (line.render->parsed() || line.devices->parsed()) start_mpi_if_launched();
  const MpiWorld& world = mpi_world();
  if (world.distributed()) {
    set_error_context(rank_label(world.rank, world.host));
    exit_at_first_signal(fmt::format("clmarch: {}: interrupted", rank_label(world.rank, world.host)));
    // mpirun forwards rank 0's stderr through a pipe to its own terminal.
    if (world.rank == 0) draw_progress_anyway();
  }
  bool coordinated = true;
  const int code = run_reporting_errors([&] {
    if (line.render->parsed()) {
      try {
        return run_render_command(line.render_options);
      } catch (const RankFailure&) {
        throw;
      } catch (...) {
        // An error before the ranks shared out the work (the options, the scene, the devices) or
        // while they did has no coordinator to tell: the job is aborted below.
        coordinated = every_rank_stopped();
        throw;
      }
    }
    if (line.check->parsed()) return run_check_command(line.check_options);
    if (line.devices->parsed()) return run_devices_command();
    if (line.bench->parsed()) return run_bench_command(line.bench_options);
    if (line.mesh->parsed()) return run_mesh_command(line.mesh_options);
    if (line.field->parsed()) return run_field_command(line.field_options);
    if (line.preview->parsed()) return run_preview_command(line.preview_options);
    return static_cast<int>(kExitOk);
  });
  if (cancellation_requested().load() && code == interrupted_exit_code()) {
    // Commands enqueued before the interrupt may still be running, or compiling: PoCL compiles a
    // kernel for its work-group size at its first enqueue, on its own threads. exit()'s static
    // destructors (LLVM's, inside PoCL) would pull the compiler from under them: a segfault or
    // "LLVM ERROR" after "clmarch: interrupted" instead of the exit code. Nothing is left to write
    // (the unwinding removed every temporary file), so leave without them.
    std::cout.flush();
    std::fflush(nullptr);
    _exit(code);
  }
  if (world.distributed() && code != kExitOk && !coordinated) {
    // The other ranks may wait for this one's report: end them all, with this code.
    std::cout.flush();
    std::fflush(nullptr);
    abort_mpi(code);
  }
  finish_mpi();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // An exception outside the commands' own reporting (setting up the options, MPI) still ends
  // with its message and kExitInternalError rather than in std::terminate.
  return clmarch::run_reporting_errors([&] { return run_main(argc, argv); });
}

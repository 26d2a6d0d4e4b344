// clmarch: the command-line entry point. Parses the command, installs the Ctrl-C handlers and
// hands errors to run_reporting_errors, which maps them to exit codes.
#include "cli/bench_command.hpp"
#include "cli/check_command.hpp"
#include "cli/devices_command.hpp"
#include "cli/error_report.hpp"
#include "cli/interrupts.hpp"
#include "cli/rank_work.hpp"
#include "cli/render_command.hpp"
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

/// An empty value (--size '', -o '') is a mistake, not the option left out, which is what CLI11
/// would take it for.
void reject_empty_values(CLI::App& command) {
  const CLI::Validator non_empty(
      [](std::string& value) { return value.empty() ? std::string("the value is empty") : std::string(); }, "",
      "NON_EMPTY");
  for (CLI::Option* option : command.get_options()) {
    if (option->get_expected_max() > 0) option->check(non_empty);
  }
}

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
  CLI::App app{"clmarch: a sphere tracer of signed distance fields on OpenCL", "clmarch"};
  app.set_version_flag("--version", std::string("clmarch ") + CLMARCH_VERSION);
  app.require_subcommand(1);
  // Global flags may also follow the subcommand: `clmarch render x.yaml --quiet`.
  app.fallthrough();
  bool quiet = false;
  bool verbose = false;
  CLI::Option* quiet_flag =
      app.add_flag("-q,--quiet", quiet, "Print nothing on success: no 'wrote' line, no progress (errors still print)");
  app.add_flag("-v,--verbose", verbose,
               "Also print the device, build options and time, driver cache hit or miss, lanes and local size")
      ->excludes(quiet_flag);
  app.footer(
      "Examples:\n"
      "  clmarch render scenes/torus.yaml                  # writes ./torus.png\n"
      "  clmarch --verbose render scenes/torus.yaml        # device, build and dispatch details on stderr\n"
      "  clmarch render scenes/torus.yaml --quiet -o t.png # silent unless it fails\n"
      "  clmarch check scenes/torus.yaml --size 160x90     # OpenCL against the CPU reference\n"
      "  clmarch bench scenes/torus.yaml --size 1280x720   # kernel times against the device's ceiling\n"
      "  clmarch devices                                   # the indices --device takes\n"
      "  clmarch --version                                 # the version, e.g. clmarch 0.3.0\n"
      "Exit codes: 0 success, 1 check failed, 2 bad input, 3 OpenCL/device fault, 4 output not written,\n"
      "70 internal error, 130 interrupted (Ctrl-C; 143 for SIGTERM). See docs/cli.md.\n"
      "Help on a command: clmarch render --help, clmarch check --help, clmarch bench --help.");
  RenderCommandOptions render_options;
  CLI::App* render = add_render_command(app, render_options);
  CheckCommandOptions check_options;
  CLI::App* check = add_check_command(app, check_options);
  CLI::App* devices = add_devices_command(app);
  BenchCommandOptions bench_options;
  CLI::App* bench = add_bench_command(app, bench_options);
  for (CLI::App* command : {render, check, bench}) reject_empty_values(*command);
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
                  << "' (expected render, check, bench or devices; see clmarch --help)\n";
        return kExitBadInput;
      }
      break;
    }
    std::cerr << "clmarch: " << one_line(e.what()) << option_suggestion(app, argc, argv) << " (see clmarch --help)\n";
    return kExitBadInput;
  }
  set_verbosity(quiet ? Verbosity::Quiet : verbose ? Verbosity::Verbose : Verbosity::Normal);
  // Under mpirun with several ranks, render and devices share the work out (docs/cli.md#mpi);
  // the other commands run whole on every rank. A plain run never starts MPI.
  if (render->parsed() || devices->parsed()) start_mpi_if_launched();
  const MpiWorld& world = mpi_world();
  if (world.distributed()) {
    set_error_context(rank_label(world.rank, world.host));
    exit_at_first_signal(fmt::format("clmarch: {}: interrupted", rank_label(world.rank, world.host)));
    // mpirun forwards rank 0's stderr through a pipe to its own terminal.
    if (world.rank == 0) draw_progress_anyway();
  }
  bool coordinated = true;
  const int code = run_reporting_errors([&] {
    if (render->parsed()) {
      try {
        return run_render_command(render_options);
      } catch (const RankFailure&) {
        throw;
      } catch (...) {
        // An error before the ranks shared out the work (the options, the scene, the devices) or
        // while they did has no coordinator to tell: the job is aborted below.
        coordinated = every_rank_stopped();
        throw;
      }
    }
    if (check->parsed()) return run_check_command(check_options);
    if (devices->parsed()) return run_devices_command();
    if (bench->parsed()) return run_bench_command(bench_options);
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

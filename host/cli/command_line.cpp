// The clmarch command line: the global flags and footer here, each command's options in its own
// cli/*_command.cpp.
#include "cli/command_line.hpp"

#include "cli/devices_command.hpp"

#include <string>

namespace clmarch {
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

}  // namespace

const char* clmarch_version() { return CLMARCH_VERSION; }

CommandLine::CommandLine() : app("clmarch: a sphere tracer of signed distance fields on OpenCL", "clmarch") {
  app.set_version_flag("--version", std::string("clmarch ") + clmarch_version());
  app.require_subcommand(1);
  // Global flags may also follow the subcommand: `clmarch render x.yaml --quiet`.
  app.fallthrough();
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
      "  clmarch mesh scenes/torus.yaml -o torus.ply       # the surface as a watertight mesh\n"
      "  clmarch field scenes/torus.yaml --points p.csv -o f.csv  # distance and colour at points\n"
      "  clmarch preview scenes/torus.yaml                 # a live view at http://127.0.0.1:8000/\n"
      "  clmarch devices                                   # the indices --device takes\n"
      "  clmarch --version                                 # the version, e.g. clmarch 0.3.0\n"
      "Exit codes: 0 success, 1 check failed, 2 bad input, 3 OpenCL/device fault, 4 output not written,\n"
      "70 internal error, 130 interrupted (Ctrl-C; 143 for SIGTERM). See docs/cli.md.\n"
      "Help on a command: clmarch render --help, clmarch check --help, clmarch bench --help, clmarch mesh --help,\n"
      "clmarch field --help, clmarch preview --help.");
  render = add_render_command(app, render_options);
  check = add_check_command(app, check_options);
  devices = add_devices_command(app);
  bench = add_bench_command(app, bench_options);
  mesh = add_mesh_command(app, mesh_options);
  field = add_field_command(app, field_options);
  preview = add_preview_command(app, preview_options);
  for (CLI::App* command : {render, check, bench, mesh, field, preview}) reject_empty_values(*command);
}

}  // namespace clmarch

// clmarch: the command-line entry point. Parses the command and maps errors to exit codes.
#include "cli/check_command.hpp"
#include "cli/devices_command.hpp"
#include "cli/render_command.hpp"
#include "common/errors.hpp"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  using namespace clmarch;
  CLI::App app{"clmarch: a sphere tracer of signed distance fields on OpenCL"};
  app.require_subcommand(1);
  RenderCommandOptions render_options;
  CLI::App* render = add_render_command(app, render_options);
  CheckCommandOptions check_options;
  CLI::App* check = add_check_command(app, check_options);
  CLI::App* devices = add_devices_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "clmarch: " << e.what() << " (see clmarch --help)\n";
    return kExitBadInput;
  }
  try {
    if (render->parsed()) return run_render_command(render_options);
    if (check->parsed()) return run_check_command(check_options);
    if (devices->parsed()) return run_devices_command();
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const DeviceError& e) {
    std::cerr << e.what() << "\n";
    return kExitDeviceFault;
  } catch (const OutputError& e) {
    std::cerr << e.what() << "\n";
    return kExitOutputFailed;
  }
  return kExitOk;
}

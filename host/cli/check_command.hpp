// `clmarch check`: renders a scene with OpenCL and with the CPU reference and compares them.
#pragma once

#include "cli/scene_options.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace clmarch {

struct CheckCommandOptions {
  SceneOptions scene;
  bool json = false;
  std::string out_dir;
};

CLI::App* add_check_command(CLI::App& app, CheckCommandOptions& options);
/// kExitOk when within the tolerances, kExitCheckFailed otherwise.
int run_check_command(const CheckCommandOptions& options);

}  // namespace clmarch

// `clmarch field`: a scene's distance and colour at the points of a CSV file, written as CSV.
#pragma once

#include "cli/scene_options.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace clmarch {

struct FieldCommandOptions {
  /// The scene file, --set, --time and --device (the image options do not apply).
  SceneOptions scene;
  std::string points;
  std::string output;
  std::string precision = "float";
  std::string backend = "opencl";
};

CLI::App* add_field_command(CLI::App& app, FieldCommandOptions& options);
int run_field_command(const FieldCommandOptions& options);

}  // namespace clmarch

// `clmarch mesh`: a scene's surface to a watertight triangle mesh file (PLY, STL, OBJ, glTF).
#pragma once

#include "cli/scene_options.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace clmarch {

struct MeshCommandOptions {
  /// The scene file, --set, --time and --device (the image options do not apply).
  SceneOptions scene;
  std::string output;
  int resolution = 256;
  std::string precision = "float";
  std::string backend = "opencl";
  std::string cells = "cubes";
  bool sharp = false;
  bool stats = false;
};

CLI::App* add_mesh_command(CLI::App& app, MeshCommandOptions& options);
int run_mesh_command(const MeshCommandOptions& options);

}  // namespace clmarch

// The clmarch command line as CLI11 objects: the global flags, the seven commands with their options,
// help texts and footers. clmarch parses with it; clmarch-docgen writes the completions and the man
// page from the same objects, so they cannot drift from the options.
#pragma once

#include "cli/bench_command.hpp"
#include "cli/check_command.hpp"
#include "cli/field_command.hpp"
#include "cli/mesh_command.hpp"
#include "cli/preview_command.hpp"
#include "cli/render_command.hpp"

#include <CLI/CLI.hpp>

namespace clmarch {

/// The parser and the values it fills in. Its options point into its own fields: it cannot be
/// copied or moved.
struct CommandLine {
  CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  CLI::App app;
  bool quiet = false;
  bool verbose = false;
  RenderCommandOptions render_options;
  CheckCommandOptions check_options;
  BenchCommandOptions bench_options;
  MeshCommandOptions mesh_options;
  FieldCommandOptions field_options;
  PreviewCommandOptions preview_options;
  CLI::App* render = nullptr;
  CLI::App* check = nullptr;
  CLI::App* devices = nullptr;
  CLI::App* bench = nullptr;
  CLI::App* mesh = nullptr;
  CLI::App* field = nullptr;
  CLI::App* preview = nullptr;
};

/// The project's version, e.g. "0.3.0" (CMakeLists.txt's project VERSION).
const char* clmarch_version();

}  // namespace clmarch

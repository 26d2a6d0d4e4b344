// `clmarch preview`: a live, interactive view of a scene in the browser, re-rendered as its files
// change (host/preview/).
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace clmarch {

struct PreviewCommandOptions {
  std::string scene_path;
  int port = 8000;
  std::string host = "127.0.0.1";
  std::optional<int> device;
  std::string size;
};

CLI::App* add_preview_command(CLI::App& app, PreviewCommandOptions& options);
/// Serves until Ctrl-C (exit code 130, as every command interrupted).
int run_preview_command(const PreviewCommandOptions& options);

}  // namespace clmarch

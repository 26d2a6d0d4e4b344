// `clmarch render`: a scene to an image and per-pixel buffers.
#pragma once

#include "cli/scene_options.hpp"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace clmarch {

struct RenderCommandOptions {
  SceneOptions scene;
  std::string output;
  std::string buffers;
  std::string backend = "opencl";
  std::string dump_kernel;
  bool stats = false;
  /// --no-image: no color image (a buffers, stats or kernel-only run).
  bool no_image = false;
  /// --frames A:B; empty: one image at --time.
  std::string frames;
  /// --fps, which needs --frames; 24 when not given.
  std::optional<double> fps;
};

/// Registers the subcommand; run_render_command does the work once parsed.
CLI::App* add_render_command(CLI::App& app, RenderCommandOptions& options);
int run_render_command(const RenderCommandOptions& options);

}  // namespace clmarch

// Options every command that renders a scene shares: the scene file, --size, --set, --device,
// --lanes, --time, --samples; and loading the scene they describe.
#pragma once

#include "api/render_session.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace clmarch {

struct SceneOptions {
  std::string scene_path;
  std::string size;
  std::vector<std::string> sets;
  std::optional<int> device;
  std::optional<int> lanes;
  /// The time t of expressions in the scene, in seconds (--time); absent: 0.
  std::optional<double> time;
  /// render.samples, overriding the scene's (--samples).
  std::optional<int> samples;
};

/// Checks an option's text is a finite decimal number that accept takes, else says
/// "must be EXPECTED (got 'TEXT')" with the text as given (1e400 is not echoed as inf).
CLI::Validator finite_number(const std::function<bool(double)>& accept, const std::string& expected);

/// Registers the shared options on a subcommand.
void add_scene_options(CLI::App& command, SceneOptions& options);

/// Loads the scene with --set applied, then --size, at time (default: --time). Throws InputError.
Scene load_scene_with_options(const SceneOptions& options, std::optional<double> time = std::nullopt);

/// The OpenCL settings the options ask for.
OpenClOptions opencl_options(const SceneOptions& options);
/// The same as a render session's.
SessionOptions session_options(const SceneOptions& options);

/// Parses "WxH" (each 1..65536); throws InputError naming --size.
std::pair<int, int> parse_size(const std::string& text);

}  // namespace clmarch

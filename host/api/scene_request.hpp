// A scene as a caller of the library asks for it: a file or text, with --set style overrides, a
// time, and an image size and sample count that override the file's. The CLI, the Python module
// and the preview load scenes through it.
#pragma once

#include "scene/scene.hpp"
#include "scene/scene_loader.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {

struct SceneRequest {
  /// The scene file; empty when text is the scene.
  std::string path;
  /// The scene's YAML or JSON text (path empty), and the name its messages start with.
  std::string text;
  std::string source_name = "<scene>";
  std::vector<SceneOverride> overrides;
  /// The time t of expressions in the scene, in seconds.
  double time = 0.0;
  /// Width and height, overriding render.width and render.height; size_label names where they
  /// came from in a message about memory (e.g. "--size 40000x40000"; empty: the scene's keys).
  std::optional<std::pair<int, int>> size;
  std::string size_label;
  /// render.samples, overriding the scene's.
  std::optional<int> samples;
};

/// Loads and validates the scene the request describes. Throws InputError ("file:line:col: ..."),
/// also when the image needs more host memory than the machine has left.
Scene load_scene(const SceneRequest& request);

/// Throws InputError, naming size_label (e.g. "--size 40000x40000") or else render.width/height
/// in the scene file, when the scene's image needs more host memory than the machine has left.
void check_host_memory(const Scene& scene, const std::string& size_label);

}  // namespace clmarch

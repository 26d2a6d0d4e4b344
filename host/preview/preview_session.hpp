// The state behind `clmarch preview`: the scene as its files are now (reloaded when one changes,
// the last good one kept while a file is broken), one render session whose programs survive
// camera moves, view changes and edits of numbers, and the last full frame's buffers for the
// page's pixel readout. The HTTP server (preview_server) only translates requests into calls here.
#pragma once

#include "api/render_session.hpp"
#include "preview/preview_view.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {

struct PreviewOptions {
  std::string scene_path;
  SessionOptions session;
  /// The full frame's size, overriding render.width/height (--size).
  std::optional<std::pair<int, int>> size;
};

/// A camera the page asks for (the contract's keys: position, look_at, up, vertical fov).
struct PreviewCamera {
  glm::dvec3 position{0.0};
  glm::dvec3 look_at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_degrees = 45.0;
};

/// One frame the page asks for.
struct FrameQuery {
  /// The page's number for it, growing: a frame asked for after it supersedes it.
  std::uint64_t sequence = 0;
  /// Absent: the scene file's camera.
  std::optional<PreviewCamera> camera;
  PreviewView view = PreviewView::Shaded;
  /// Absent: the time of the last frame (0 at first).
  std::optional<double> time;
  /// A quarter of the size each way and one sample a pixel: the first answer to a move.
  bool coarse = false;
};

struct PreviewFrame {
  std::vector<unsigned char> png;
  nlohmann::json stats;
};

/// Throws InputError unless the camera can be rendered (finite, fov in (0, 180), a view direction
/// and an up vector not along it).
void check_preview_camera(const PreviewCamera& camera);

class PreviewSession {
 public:
  /// Loads the scene; throws InputError when it cannot (a preview starts from a good file).
  explicit PreviewSession(PreviewOptions options);

  /// Loads the scene again when its file or an instance file changed since the last look; a
  /// broken file keeps the last good scene and sets the error the page shows. Returns whether it
  /// loaded (or failed to).
  bool refresh();
  /// What the page polls: the scene's version (it grows with each load), its error, camera, size,
  /// whether it is animated, the newest frame number asked for (a page loaded later numbers its
  /// frames after it) and the last frame's figures.
  nlohmann::json state();
  /// Renders the query; nothing when a newer query came first (it would show an old camera).
  std::optional<PreviewFrame> frame(const FrameQuery& query);
  /// The last full frame's buffers at pixel (x, y): depth, steps, id, status, position, normal;
  /// nothing outside it or before the first full frame.
  std::optional<nlohmann::json> pixel(int x, int y);

 private:
  struct WatchedFile {
    std::filesystem::file_time_type time;
    std::uintmax_t size = 0;
    bool exists = false;
  };
  std::map<std::string, WatchedFile> look_at_files() const;
  Scene load(double time) const;

  PreviewOptions options_;
  std::mutex state_mutex_;
  Scene scene_;
  std::uint64_t version_ = 1;
  std::string error_;
  std::map<std::string, WatchedFile> watched_;
  nlohmann::json last_stats_;

  std::atomic<std::uint64_t> latest_sequence_{0};
  std::mutex render_mutex_;
  RenderSession session_;
  struct FullFrame {
    FrameBuffers buffers;
    Camera camera;
  };
  std::optional<FullFrame> last_full_;
};

}  // namespace clmarch

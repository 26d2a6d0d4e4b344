// The preview's HTTP server (cpp-httplib): the page, its frames, pixel readouts and state, nothing
// else. Every request is a GET with known parameters; anything else is answered with an error
// status and a one-line message, never with a file of the machine or a crash.
#pragma once

#include "preview/preview_session.hpp"

#include <functional>
#include <memory>
#include <string>

namespace clmarch {

class PreviewServer {
 public:
  explicit PreviewServer(PreviewSession& session);
  ~PreviewServer();
  PreviewServer(const PreviewServer&) = delete;
  PreviewServer& operator=(const PreviewServer&) = delete;

  /// Binds host:port (port 0: any free one); returns the port, or throws InputError naming
  /// --host and --port when it cannot.
  int bind(const std::string& host, int port);
  /// Serves until stop() (from another thread). Blocks; false when listening failed.
  bool serve();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The query string's parameters of a frame request, checked: seq (required), view, coarse (0 or
/// 1), t, and pos, look, up (three numbers each, comma-separated) with fov, all four or none.
/// Throws InputError naming the parameter.
FrameQuery parse_frame_query(const std::multimap<std::string, std::string>& params);

}  // namespace clmarch

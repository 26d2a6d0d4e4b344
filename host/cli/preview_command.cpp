// `clmarch preview`.
#include "cli/preview_command.hpp"

#include "cli/scene_options.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "preview/preview_server.hpp"
#include "preview/preview_session.hpp"

#include <fmt/format.h>

#include <chrono>
#include <thread>

namespace clmarch {

CLI::App* add_preview_command(CLI::App& app, PreviewCommandOptions& options) {
  CLI::App* preview =
      app.add_subcommand("preview", "Serve a live view of a scene in the browser, re-rendered as its files change");
  preview->footer(
      "Open the address it prints. The camera follows the mouse without rebuilding the program; a saved scene\n"
      "file re-renders, a broken one shows its error while the last good picture stays. Ctrl-C stops it.\n"
      "Examples:\n"
      "  clmarch preview scenes/torus.yaml                     # http://127.0.0.1:8000/\n"
      "  clmarch preview scenes/mechanical_part.yaml --port 8080 --size 960x540\n"
      "  clmarch preview scenes/moving_shapes.yaml --device 0  # a time slider for animated scenes");
  preview->add_option("scene", options.scene_path, "Scene file (YAML or JSON), e.g. scenes/torus.yaml")
      ->required()
      ->type_name("FILE");
  preview->add_option("--port", options.port, "TCP port to listen on (default 8000; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  preview->add_option("--host", options.host,
                      "Address to listen on (default 127.0.0.1, this machine only; another address lets other "
                      "machines in, with a warning)");
  preview->add_option("--device", options.device,
                      "OpenCL device index from `clmarch devices` (default: first GPU, else first CPU)");
  preview->add_option("--size", options.size,
                      "Size WxH of the full frame, overriding render.width/height (e.g. --size 960x540)");
  return preview;
}

int run_preview_command(const PreviewCommandOptions& options) {
  PreviewOptions preview;
  preview.scene_path = options.scene_path;
  preview.session.device = options.device;
  if (!options.size.empty()) preview.size = parse_size(options.size);
  PreviewSession session(preview);
  PreviewServer server(session);
  const int port = server.bind(options.host, options.port);
  if (options.host != "127.0.0.1" && options.host != "localhost" && options.host != "::1") {
    log_warning(
        fmt::format("--host {}: other machines can reach the preview (it serves the scene's pictures and "
                    "buffers to anyone who asks)",
                    options.host));
  }
  const std::string host = options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host;
  log_info(fmt::format("preview of {} at http://{}:{}/ (Ctrl-C stops it)", options.scene_path, host, port));
  // Ctrl-C sets the cancellation flag (cli/interrupts); this thread stops the server on it, and
  // looks at the scene's files meanwhile, so that a save re-renders without a request to ask.
  std::thread watcher([&] {
    while (!cancellation_requested().load()) {
      session.refresh();
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    server.stop();
  });
  const bool served = server.serve();
  const bool interrupted = cancellation_requested().exchange(true);
  watcher.join();
  if (!served && !interrupted) throw std::runtime_error("the preview server stopped listening");
  log_info("preview stopped");
  throw Cancelled();
}

}  // namespace clmarch

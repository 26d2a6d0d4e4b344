// The outputs of `clmarch render`.
#include "cli/render_outputs.hpp"

#include "api/stats_json.hpp"
#include "common/cancellation.hpp"
#include "common/log.hpp"
#include "common/atomic_file.hpp"
#include "image/image_writer.hpp"
#include "frame/views.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>
#include <string>
#include <vector>

namespace clmarch {

void write_outputs(const FrameFiles& files, const Scene& scene, FrameBuffers& buffers) {
  // A Ctrl-C that came too late for the renderer's own checks still writes nothing.
  throw_if_cancelled();
  if (files.output.empty() && files.buffers.empty()) return;  // --no-image with --stats, or --dump-kernel alone
  apply_view(buffers, scene.shading.view, scene.render);
  // Both files are written before either replaces its target: a failure leaves both as they were.
  StagedFiles written;
  std::vector<std::string> names;
  if (!files.output.empty()) {
    write_color_image(written, files.output, buffers);
    names.push_back(files.output);
  }
  if (!files.buffers.empty()) {
    write_buffers_exr(written, files.buffers, buffers, scene);
    names.push_back(files.buffers);
  }
  written.commit();
  if (!names.empty()) log_info(fmt::format("wrote {}", fmt::join(names, " and ")));
}

nlohmann::json stats_json(const RenderCommandOptions& options, const Scene& scene, const RenderStats& s) {
  return render_stats_json(backend_of(options), scene, s);
}

Backend backend_of(const RenderCommandOptions& options) { return parse_backend(options.backend, "--backend"); }

void print_json_line(const nlohmann::json& json) {
  const std::string line = json.dump() + "\n";
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fflush(stdout);
}

}  // namespace clmarch

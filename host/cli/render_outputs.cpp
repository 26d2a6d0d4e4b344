// The outputs of `clmarch render`.
#include "cli/render_outputs.hpp"

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

KernelPurpose purpose_for(const Scene& scene, bool want_buffers) {
  switch (scene.shading.view) {
    case View::Shaded:
      return want_buffers ? KernelPurpose::Buffers : KernelPurpose::Color;
    // The samples a pixel gets follow its color's edges: the shaded program decides them.
    case View::Samples:
      return want_buffers ? KernelPurpose::Buffers : KernelPurpose::Color;
    case View::Normals:
      return KernelPurpose::Normals;
    // The status view's program writes the status plane (Normals does).
    case View::Status:
      return KernelPurpose::Normals;
    case View::Depth:
    case View::Steps:
      return want_buffers ? KernelPurpose::Normals : KernelPurpose::DepthSteps;
  }
  return KernelPurpose::Shaded;
}

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
  return {{"backend", options.backend},
          {"device", s.device},
          {"lanes", s.lanes},
          {"precision", options.backend == "reference" ? "double" : kPrecisionNames[static_cast<int>(s.precision)]},
          {"width", scene.render.width},
          {"height", scene.render.height},
          {"build_ms", s.build_ms},
          {"kernel_ms", s.kernel_ms},
          {"steps", s.steps},
          {"rays_per_s", s.rays_per_s},
          {"chunks", s.chunks},
          {"literals", s.literals},
          {"surface_steps", s.steps - s.wall_steps},
          {"wall_steps", s.wall_steps},
          {"coarse_steps", s.coarse_steps},
          {"out_of_steps", s.out_of_steps},
          {"out_of_distance", s.out_of_distance}};
}

void print_json_line(const nlohmann::json& json) {
  const std::string line = json.dump() + "\n";
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fflush(stdout);
}

}  // namespace clmarch

// `clmarch render`.
#include "cli/render_command.hpp"

#include "common/errors.hpp"
#include "image/atomic_file.hpp"
#include "image/image_writer.hpp"
#include "reference/reference_renderer.hpp"
#include "render/views.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>

namespace clmarch {
namespace {

/// The kernel work the outputs need: buffers include normals, the image needs what its view shows.
KernelPurpose purpose_for(const Scene& scene, bool want_buffers) {
  switch (scene.shading.view) {
    case View::Shaded: return KernelPurpose::Shaded;
    case View::Normals: return KernelPurpose::Normals;
    default: return want_buffers ? KernelPurpose::Normals : KernelPurpose::DepthSteps;
  }
}

}  // namespace

CLI::App* add_render_command(CLI::App& app, RenderCommandOptions& options) {
  CLI::App* render = app.add_subcommand("render", "Render a scene to an image and per-pixel buffers");
  render->footer(
      "Examples:\n"
      "  clmarch render scenes/torus.yaml -o torus.png\n"
      "  clmarch render scenes/torus.yaml --size 1280x720 --buffers torus.exr --stats\n"
      "  clmarch render scenes/torus.yaml --set render.epsilon=1e-5 --set shading.view=normals -o n.png");
  add_scene_options(*render, options.scene);
  render->add_option("-o,--output", options.output,
                     "Color image; the format follows the extension (exr, hdr: linear float; png, jpg, tif and the "
                     "other formats OpenImageIO writes: 8-bit sRGB). "
                     "Default: SCENE_NAME.png in the current folder");
  render->add_option("--buffers", options.buffers, "Write all buffers to one float EXR: R, G, B, depth, steps, N.x, N.y, N.z");
  render->add_option("--backend", options.backend, "opencl, or reference (the double-precision CPU renderer)")
      ->check(CLI::IsMember({"opencl", "reference"}));
  render->add_option("--dump-kernel", options.dump_kernel, "Write the exact OpenCL C source that is built");
  render->add_flag("--stats", options.stats, "Print one JSON line of figures on stdout");
  return render;
}

int run_render_command(const RenderCommandOptions& options) {
  std::string output = options.output;
  if (output.empty()) output = std::filesystem::path(options.scene.scene_path).stem().string() + ".png";
  check_image_path(output, "--output");
  if (options.backend == "reference") {
    for (const auto& [given, name] : {std::pair{options.scene.device.has_value(), "--device"},
                                      std::pair{options.scene.lanes.has_value(), "--lanes"},
                                      std::pair{!options.dump_kernel.empty(), "--dump-kernel"}}) {
      if (given) throw InputError(fmt::format("{} applies to the OpenCL backend, not to --backend reference", name));
    }
  }
  if (!options.buffers.empty()) {
    std::string extension = std::filesystem::path(options.buffers).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension != ".exr") {
      throw InputError(fmt::format("--buffers {}: the buffers file must be an .exr", options.buffers));
    }
    check_output_folder(options.buffers, "--buffers");
  }
  if (!options.dump_kernel.empty()) check_output_folder(options.dump_kernel, "--dump-kernel");

  const Scene scene = load_scene_with_options(options.scene);
  RenderResult result;
  if (options.backend == "reference") {
    const auto start = std::chrono::steady_clock::now();
    result.buffers = render_reference(scene);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    result.stats.device = "CPU reference (double)";
    result.stats.kernel_ms = ms;
    for (float s : result.buffers.plane(Channel::Steps)) result.stats.steps += static_cast<std::uint64_t>(s);
    for (float s : result.buffers.plane(Channel::WallSteps)) result.stats.wall_steps += static_cast<std::uint64_t>(s);
    result.stats.rays_per_s = static_cast<double>(scene.render.width) * scene.render.height / (ms * 1e-3);
  } else {
    OpenClOptions cl = opencl_options(options.scene);
    cl.purpose = purpose_for(scene, !options.buffers.empty());
    cl.dump_kernel_path = options.dump_kernel;
    result = render_opencl(scene, cl);
  }
  apply_view(result.buffers, scene.shading.view, scene.render);

  write_color_image(output, result.buffers);
  if (!options.buffers.empty()) write_buffers_exr(options.buffers, result.buffers);
  std::cerr << fmt::format("clmarch: wrote {}{}\n", output, options.buffers.empty() ? "" : " and " + options.buffers);

  if (options.stats) {
    const RenderStats& s = result.stats;
    nlohmann::json line = {{"backend", options.backend}, {"device", s.device},         {"lanes", s.lanes},
                           {"width", scene.render.width}, {"height", scene.render.height}, {"build_ms", s.build_ms},
                           {"kernel_ms", s.kernel_ms},  {"steps", s.steps},            {"rays_per_s", s.rays_per_s},
                           {"chunks", s.chunks}, {"surface_steps", s.steps - s.wall_steps}, {"wall_steps", s.wall_steps}};
    std::cout << line.dump() << std::endl;
  }
  return kExitOk;
}

}  // namespace clmarch

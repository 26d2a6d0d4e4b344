// `clmarch render`.
#include "cli/render_command.hpp"

#include "cli/frame_sequence.hpp"
#include "cli/rank_work.hpp"
#include "cli/render_outputs.hpp"
#include "cli/render_tiles.hpp"

#include "cl/devices.hpp"
#include "common/atomic_file.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "common/progress.hpp"
#include "distributed/mpi_world.hpp"
#include "distributed/rank_device.hpp"
#include "distributed/work_queue.hpp"
#include "frame/views.hpp"
#include "image/image_writer.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/scene_box.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>

namespace clmarch {

CLI::App* add_render_command(CLI::App& app, RenderCommandOptions& options) {
  CLI::App* render = app.add_subcommand("render", "Render a scene to an image and per-pixel buffers");
  render->footer(
      "Examples:\n"
      "  clmarch render scenes/torus.yaml                          # writes ./torus.png\n"
      "  clmarch render scenes/torus.yaml -o torus.exr             # linear float image\n"
      "  clmarch render scenes/torus.yaml --size 1280x720 --buffers torus.exr --stats\n"
      "  clmarch render scenes/torus.yaml --set render.epsilon=1e-5 --set shading.view=normals -o n.png\n"
      "  clmarch render scenes/torus.yaml --backend reference -o ref.png   # CPU, double precision\n"
      "  clmarch render scenes/torus.yaml --device 0 --lanes 1     # one pixel per work-item\n"
      "  clmarch render scenes/torus.yaml --dump-kernel torus.cl   # only the OpenCL C that is built\n"
      "  clmarch render scenes/torus.yaml --no-image --buffers torus.exr   # the buffers alone\n"
      "  clmarch render scenes/moving_shapes.yaml --time 1.5       # t = 1.5 in the scene's expressions\n"
      "  clmarch render scenes/torus.yaml --samples 16 --buffers torus.exr   # anti-aliased, coverage in A\n"
      "  clmarch render scenes/moving_shapes.yaml --frames 0:47 --fps 24 -o frames/shot_####.png\n"
      "  mpirun -n 4 clmarch render scenes/moving_shapes.yaml --frames 0:47 -o frames/shot_####.png   # over 4 MPI "
      "ranks\n"
      "  clmarch render scenes/torus.yaml --quiet                  # nothing on stderr unless it fails\n"
      "  clmarch render scenes/torus.yaml --verbose                # device, build, cache, lanes, local size\n"
      "Ctrl-C stops the render and writes nothing (exit code 130). Options: docs/cli.md.");
  add_scene_options(*render, options.scene);
  render
      ->add_option("-o,--output", options.output,
                   "Color image; the format follows the extension (exr, hdr: linear float; png, jpg, tif and the "
                   "other formats OpenImageIO writes: 8-bit sRGB). "
                   "Default: SCENE_NAME.png in the current folder (e.g. -o torus.exr)")
      ->type_name("FILE");
  render
      ->add_option(
          "--buffers", options.buffers,
          "Write all buffers to one float EXR: R, G, B, depth, steps, N.x, N.y, N.z (e.g. --buffers torus.exr)")
      ->type_name("FILE");
  render
      ->add_option("--backend", options.backend,
                   "opencl (default), or reference: the double-precision CPU renderer, which needs no OpenCL "
                   "(e.g. --backend reference)")
      ->check(CLI::IsMember({"opencl", "reference"}));
  render
      ->add_option("--dump-kernel", options.dump_kernel,
                   "Write the exact OpenCL C source that is built, before building it; without -o no image is "
                   "written, and without --buffers or --stats nothing renders (e.g. --dump-kernel torus.cl)")
      ->type_name("FILE");
  render->add_flag("--no-image", options.no_image,
                   "Write no color image: for --buffers, --stats or --dump-kernel alone (e.g. --no-image --stats)");
  render->add_option(
      "--frames", options.frames,
      "Render frames FIRST:LAST (both included) of an animation, frame n at t = n / fps, to numbered "
      "files: a run of # in -o/--buffers/--dump-kernel is the frame number (-o shot_####.png), else _NNNN goes "
      "before the extension (e.g. --frames 0:47 --fps 24)");
  // Checked against --frames in check_render_options: CLI11's needs() would garble the help line.
  render->add_option("--fps", options.fps, "Frames per second of --frames (default 24; e.g. --fps 30)")
      ->check(finite_number([](double fps) { return fps > 0.0 && fps <= 1000.0; }, "frames per second in (0, 1000]"));
  render->add_flag("--stats", options.stats,
                   "Print one JSON line of figures on stdout: device, lanes, build_ms, kernel_ms, steps, rays_per_s");
  return render;
}

namespace {

/// Refuses two of the output files (empty: not written) being one file: one would overwrite the other.
void check_distinct_outputs(const std::string& output, const std::string& buffers, const std::string& dump_kernel) {
  const std::pair<std::string, const char*> outputs[] = {
      {output, "--output"}, {buffers, "--buffers"}, {dump_kernel, "--dump-kernel"}};
  for (std::size_t a = 0; a < std::size(outputs); ++a) {
    for (std::size_t b = a + 1; b < std::size(outputs); ++b) {
      if (outputs[a].first.empty() || outputs[b].first.empty()) continue;
      std::error_code error;
      const auto resolved = [&](const std::string& path) {
        return std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error);
      };
      const bool same = resolved(outputs[a].first) == resolved(outputs[b].first);
      if (same) {
        throw InputError(fmt::format("{} and {} are the same file {}: one would overwrite the other", outputs[a].second,
                                     outputs[b].second, outputs[b].first));
      }
    }
  }
}

/// Refuses option combinations that cannot apply, before anything is loaded or written.
void check_render_options(const RenderCommandOptions& options, const std::string& output) {
  // Other tools take -o /dev/null for "no image"; here the image would be renamed over the device.
  if (is_special_file(output)) {
    throw InputError(
        fmt::format("--output {}: is a device, pipe or socket, not an image file: to render without "
                    "writing an image, use --no-image (with --stats, --buffers or --dump-kernel)",
                    output));
  }
  if (!output.empty()) check_image_path(output, "--output");
  if (options.backend == "reference") {
    for (const auto& [given, name] : {std::pair{options.scene.device.has_value(), "--device"},
                                      std::pair{options.scene.lanes.has_value(), "--lanes"},
                                      std::pair{!options.dump_kernel.empty(), "--dump-kernel"}}) {
      if (given) throw InputError(fmt::format("{} applies to the OpenCL backend, not to --backend reference", name));
    }
  }
  if (!options.buffers.empty()) {
    std::string extension = std::filesystem::path(options.buffers).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (extension != ".exr") {
      throw InputError(fmt::format("--buffers {}: the buffers file must be an .exr", options.buffers));
    }
    check_output_folder(options.buffers, "--buffers");
  }
  if (!options.dump_kernel.empty()) check_output_folder(options.dump_kernel, "--dump-kernel");
  check_distinct_outputs(output, options.buffers, options.dump_kernel);
  if (!options.frames.empty() && options.scene.time) {
    throw InputError("--time and --frames both set the time: --frames renders frame n at t = n / fps");
  }
  if (options.fps && options.frames.empty()) throw InputError("--fps requires --frames: it sets the frames' times");
  if (options.no_image && !options.output.empty())
    throw InputError("--no-image and --output both given: write an image or not");
  if (options.no_image && options.buffers.empty() && !options.stats && options.dump_kernel.empty()) {
    throw InputError("--no-image leaves nothing to write: add --buffers, --stats or --dump-kernel");
  }
}

/// Renders scene with the options' backend in session (which keeps the program for the next
/// frame); a --dump-kernel run without outputs builds the program and renders nothing.
RenderResult render_scene(const RenderCommandOptions& options, const Scene& scene, const FrameFiles& files,
                          RenderSession& session) {
  FrameRequest request;
  request.backend = backend_of(options);
  request.buffers = !files.buffers.empty();
  request.ray_status = options.stats;
  if (!files.dump_kernel.empty()) {
    request.on_source = [path = files.dump_kernel](const std::string& source) { write_file_atomically(path, source); };
  }
  if (files.output.empty() && files.buffers.empty() && !options.stats) {
    // A --dump-kernel run: the program is built (its build log shows any error), nothing rendered.
    session.prepare(scene, request);
    return {};
  }
  RenderResult result = session.render(scene, request);
  if (request.backend == Backend::OpenCl) {
    // The renderer's dispatch takes default_local_size for its work-groups (render/dispatch_plan.cpp).
    log_verbose(fmt::format("lanes {} (pixels per work-item), local size {}, stages {}, {} chunk{}, kernel {:.1f} ms",
                            result.stats.lanes, default_local_size(select_device(options.scene.device)),
                            result.stats.stages, result.stats.chunks, result.stats.chunks == 1 ? "" : "s",
                            result.stats.kernel_ms));
  }
  return result;
}

/// How camera rays march, and what the automatic settings chose, for --verbose.
std::string march_summary(const Scene& scene) {
  std::string where = "from the camera (unbounded)";
  if (uses_cells_tiling(scene)) {
    where = "through the cells of the tiling";
  } else if (const std::optional<BoundingSphere> bounds = camera_ray_bounds(scene)) {
    where = fmt::format("inside a bounding sphere of radius {:.4g}{}", bounds->radius,
                        camera_ray_box(scene) ? " and a bounding box" : "");
  }
  const RenderSettings chosen = resolved_render_settings(scene);
  return fmt::format("march: {}, coarse pass {}{}, over-relaxation {:g}{}", where,
                     kCoarsePassNames[static_cast<int>(chosen.coarse_pass)],
                     scene.render.coarse_pass == CoarsePass::Auto ? " (auto)" : "", *chosen.over_relaxation,
                     scene.render.over_relaxation ? "" : " (auto)");
}

/// Renders and writes one image (and its buffers); frame is set for sequences. Returns its figures.
RenderStats render_image(const RenderCommandOptions& options, const Scene& scene, const FrameFiles& files,
                         std::optional<int> frame, RenderSession& session) {
  RenderResult result = render_scene(options, scene, files, session);
  write_outputs(files, scene, result.buffers);
  if (options.stats) {
    nlohmann::json line = stats_json(options, scene, result.stats);
    if (frame) {
      line["frame"] = *frame;
      line["time"] = scene.time;
    }
    if (mpi_world().distributed()) {
      line["rank"] = mpi_world().rank;
      line["host"] = mpi_world().host;
    }
    print_json_line(line);
  }
  return result.stats;
}

/// The numbered files of one frame of a sequence, checked as names (their folders were checked
/// with the options).
FrameFiles frame_files(const RenderCommandOptions& options, const std::string& output, int frame,
                       const FrameRange& range) {
  FrameFiles files;
  if (!output.empty()) {
    files.output = frame_path(output, frame, range);
    check_output_name(files.output, "--output");
  }
  if (!options.buffers.empty()) {
    files.buffers = frame_path(options.buffers, frame, range);
    check_output_name(files.buffers, "--buffers");
  }
  if (!options.dump_kernel.empty()) {
    files.dump_kernel = frame_path(options.dump_kernel, frame, range);
    check_output_name(files.dump_kernel, "--dump-kernel");
  }
  check_distinct_outputs(files.output, files.buffers, files.dump_kernel);
  return files;
}

/// Frames compared before a sequence renders, to find the literals that vary (a load costs little
/// next to a program build).
constexpr int kSampledFrames = 64;

/// The frames of --frames, in turn in one process, or handed out to the ranks of an MPI job as
/// they come free (each rank writes its own). Each image is complete before the next begins, so a
/// Ctrl-C leaves the finished frames and nothing of the ones in progress.
void render_sequence(const RenderCommandOptions& options, const std::string& output) {
  const FrameRange range = parse_frame_range(options.frames, options.fps.value_or(24.0));
  RenderSession session(session_options(options.scene));
  // Every frame is loaded, and so checked, before the first renders: a scene that breaks at some
  // time fails with nothing written (a load costs little next to a render). Knowing up front
  // which literals vary, the frames of one shape build one program between them (OpenCL).
  const std::vector<int> sampled = sample_frames(range, kSampledFrames);
  // So are the frames' files: a numbered name can be an existing folder, or longer than a folder takes.
  double pixels = 0.0;
  for (int frame = range.first; frame <= range.last; ++frame) {
    throw_if_cancelled();
    frame_files(options, output, frame, range);
    const Scene scene = load_scene_with_options(options.scene, range.time_of(frame));
    pixels = static_cast<double>(scene.render.width) * scene.render.height;
    if (options.backend == "opencl" && std::binary_search(sampled.begin(), sampled.end(), frame)) {
      session.expect_frame(scene);
    }
  }
  // Rank 0 counts every rank's frames.
  std::optional<ProgressLine> progress;
  if (mpi_world().rank == 0) progress.emplace("frames", range.count(), pixels);
  const UnitName name = [&](int unit) { return fmt::format("frame {}", range.first + unit); };
  const std::unique_ptr<WorkQueue> queue = make_work_queue(
      range.count(), [&](int, int, const UnitFigures&, std::span<const float>) { progress->count(); }, name);
  render_units(
      *queue,
      [&](int unit) {
        const int frame = range.first + unit;
        const Scene scene = load_scene_with_options(options.scene, range.time_of(frame));
        const FrameFiles files = frame_files(options, output, frame, range);
        log_verbose(fmt::format("frame {} at t = {} s", frame, scene.time));
        const RenderStats stats = render_image(options, scene, files, frame, session);
        queue->done(unit, UnitFigures{stats, pixels, ""}, {});
        throw_if_cancelled();
      },
      name);
}

}  // namespace

int run_render_command(const RenderCommandOptions& given) {
  RenderCommandOptions options = given;
  check_render_options(options, options.output);
  // The color image: -o's, else SCENE_NAME.png, except for --no-image and a --dump-kernel run.
  std::string output = options.output;
  if (output.empty() && !options.no_image && options.dump_kernel.empty()) {
    output = std::filesystem::path(options.scene.scene_path).stem().string() + ".png";
    check_image_path(output, "--output");
  }
  const MpiWorld& world = mpi_world();
  if (world.distributed() && options.backend == "opencl" && !options.scene.device) {
    options.scene.device = rank_default_device(list_devices(), world.local_rank);
  }
  if (!options.frames.empty()) {
    render_sequence(options, output);
    return kExitOk;
  }
  const Scene scene = load_scene_with_options(options.scene);
  log_verbose(fmt::format("scene {}: {}x{} pixels, max_steps {}", options.scene.scene_path, scene.render.width,
                          scene.render.height, scene.render.max_steps));
  log_verbose(march_summary(scene));
  const FrameFiles files{output, options.buffers, options.dump_kernel};
  const bool kernel_only = output.empty() && options.buffers.empty() && !options.stats;
  if (world.distributed() && options.backend == "opencl" && !kernel_only) {
    render_image_in_tiles(options, scene, files);
  } else if (world.rank == 0) {
    // The CPU reference renders whole images only, and a --dump-kernel run renders nothing: under
    // MPI, rank 0 does either alone.
    RenderSession session(session_options(options.scene));
    render_image(options, scene, files, std::nullopt, session);
  }
  return kExitOk;
}

}  // namespace clmarch

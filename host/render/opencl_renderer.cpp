// The OpenCL render path: one march dispatch per chunk of rows, planar buffers (one plane per
// channel) read back into the frame.
#include "render/opencl_renderer.hpp"

#include "cl/cl_errors.hpp"
#include "common/cancellation.hpp"
#include "common/log.hpp"
#include "common/progress.hpp"
#include "frame/antialias.hpp"
#include "render/cone_pass.hpp"
#include "render/device_inputs.hpp"
#include "render/dispatch_plan.hpp"
#include "render/prepared_program.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace clmarch {
namespace {

std::uint64_t plane_total(const std::vector<float>& plane) {
  return std::accumulate(plane.begin(), plane.end(), std::uint64_t{0},
                         [](std::uint64_t sum, float s) { return sum + static_cast<std::uint64_t>(s); });
}

}  // namespace

struct OpenClRenderer::State {
  /// The scene's settings; not its tree, which the program holds (a million primitives' tree is
  /// hundreds of megabytes, and a copy of it set the process's peak memory).
  RenderSettings render;
  OpenClOptions options;
  bool rendered = false;
  PreparedProgram prepared;
  Dispatch dispatch;
  MarchParams params;
  cl::Buffer out;
  cl::Buffer lights;
  std::optional<cl::Buffer> values;
  cl::Kernel kernel;
  std::optional<ConePass> cones;
  /// ANTIALIAS programs: which pixels of the image a refining pass marches (one byte each), and
  /// the packets of a chunk it runs over.
  std::optional<cl::Buffer> sample_mask;
  std::optional<cl::Buffer> refine_packets;
  /// Whether the coarse pass ran for the current scene (render_rows runs it at the first band).
  bool cones_run = false;
};

OpenClRenderer::OpenClRenderer(const Scene& scene, const OpenClOptions& options) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.render = scene.render;
  s.options = options;
  s.prepared = prepare_program(scene, options, options.purpose);
  DeviceProgram& dp = s.prepared.program;
  const std::size_t chunk_limit = options.max_chunk_pixels ? options.max_chunk_pixels : chunk_pixels_for(dp.device);
  s.dispatch = plan_tile_dispatch(s.prepared, scene.render.width, scene.render.height, chunk_limit);
  s.params = march_params(scene, s.dispatch);
  const std::vector<cl_float4> lights = light_data(scene);
  with_device_errors(dp.device, [&] {
    s.out = cl::Buffer(dp.context, CL_MEM_WRITE_ONLY | CL_MEM_HOST_READ_ONLY, march_output_bytes(s.dispatch));
    s.lights = cl::Buffer(dp.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lights.size() * sizeof(cl_float4),
                          const_cast<cl_float4*>(lights.data()));
    s.values = make_scene_values(s.prepared, scene);
    s.kernel = cl::Kernel(dp.program, "march");
    s.cones = make_cone_pass(s.prepared, scene, s.values);
    const int next_arg = bind_march_inputs(s.kernel, s.out, s.lights, s.values, s.cones);
    if (uses_antialiasing(scene, options.purpose)) {
      const std::size_t pixels = static_cast<std::size_t>(scene.render.width) * scene.render.height;
      s.sample_mask = cl::Buffer(dp.context, CL_MEM_READ_ONLY, pixels);
      s.refine_packets = cl::Buffer(dp.context, CL_MEM_READ_ONLY,
                                    s.dispatch.global_items * s.prepared.packets_per_item * sizeof(cl_int));
      s.kernel.setArg(next_arg, *s.sample_mask);
      s.kernel.setArg(next_arg + 1, *s.refine_packets);
    }
  });
}

OpenClRenderer::~OpenClRenderer() = default;

bool OpenClRenderer::can_render(const Scene& scene, const OpenClOptions& options) const {
  const State& s = *state_;
  const OpenClOptions& mine = s.options;
  if (scene.render.width != s.render.width || scene.render.height != s.render.height) return false;
  if (options.device != mine.device || options.lanes != mine.lanes || options.purpose != mine.purpose ||
      !(options.variant == mine.variant) || options.max_chunk_pixels != mine.max_chunk_pixels ||
      options.value_slots != mine.value_slots) {
    return false;
  }
  return generate_kernel_source(scene, s.prepared.kernel_options) == s.prepared.source;
}

void OpenClRenderer::set_scene(const Scene& scene) {
  State& s = *state_;
  s.render = scene.render;
  s.cones_run = false;
  s.params = march_params(scene, s.dispatch);
  // The same source has the same LIGHT_COUNT, so the buffer keeps its size.
  const std::vector<cl_float4> lights = light_data(scene);
  with_device_errors(s.prepared.program.device, [&] {
    s.prepared.program.queue.enqueueWriteBuffer(s.lights, CL_TRUE, 0, lights.size() * sizeof(cl_float4), lights.data());
    write_scene_values(s.prepared, scene, s.values);
  });
}

const std::string& OpenClRenderer::source() const { return state_->prepared.source; }

namespace {

/// The packets (row-major tiles of the chunk of rows first_row .. first_row + rows - 1, as the
/// march kernel numbers them) that hold a pixel refine flags, padded for the dispatch of dispatch's
/// work-group size with a packet past the chunk.
std::vector<cl_int> packets_to_refine(const std::vector<std::uint8_t>& refine, int width, int band_first_row, int first_row,
                                      int rows, const Dispatch& dispatch, int packets_per_item) {
  const int tiles_per_row = (width + dispatch.tile_width - 1) / dispatch.tile_width;
  std::vector<cl_int> packets;
  for (int row = 0; row < rows; ++row) {
    const std::size_t at = static_cast<std::size_t>(first_row - band_first_row + row) * width;
    for (int x = 0; x < width; ++x) {
      if (!refine[at + x]) continue;
      packets.push_back((row / dispatch.tile_height) * tiles_per_row + x / dispatch.tile_width);
    }
  }
  std::sort(packets.begin(), packets.end());
  packets.erase(std::unique(packets.begin(), packets.end()), packets.end());
  if (packets.empty()) return packets;
  const std::size_t group = dispatch.local_items * packets_per_item;
  const cl_int past_the_chunk = (dispatch.chunk_rows / dispatch.tile_height + 1) * tiles_per_row;
  packets.resize((packets.size() + group - 1) / group * group, past_the_chunk);
  return packets;
}

/// The refining passes of an anti-aliased render of rows band_first_row .. end_row - 1, whose
/// centre rays are in buffers: samples 1 .. N - 1 of the pixels pixels_to_refine flags, one
/// dispatch of the march kernel per sample and chunk over the packets that hold such pixels, their
/// means written into buffers. Returns the passes' kernel time.
double refine_samples(const RenderSettings& render, PreparedProgram& prepared, cl::Kernel& kernel, const cl::Buffer& out,
                      const cl::Buffer& sample_mask, const cl::Buffer& refine_packets, MarchParams params,
                      const Dispatch& dispatch, int band_first_row, int end_row, FrameBuffers& buffers) {
  const int count = render.samples;
  SampleSums sums(buffers, pixels_to_refine(buffers, render.adaptive));
  const std::vector<std::uint8_t>& refine = sums.refine();
  double kernel_ms = 0.0;
  if (std::find(refine.begin(), refine.end(), 1) != refine.end()) {
    DeviceProgram& dp = prepared.program;
    const int width = buffers.width;
    const bool color = std::find(prepared.planes.begin(), prepared.planes.end(), CLMARCH_CHANNEL_R) != prepared.planes.end();
    const std::size_t band_offset = static_cast<std::size_t>(band_first_row) * width;
    dp.queue.enqueueWriteBuffer(sample_mask, CL_TRUE, band_offset, refine.size(), refine.data());
    std::vector<float> depth(dispatch.plane_stride), r(dispatch.plane_stride), g(dispatch.plane_stride), b(dispatch.plane_stride);
    const auto read_plane = [&](int channel, std::size_t floats, std::vector<float>& into) {
      dp.queue.enqueueReadBuffer(out, CL_FALSE, channel * dispatch.plane_stride * sizeof(float), floats * sizeof(float), into.data());
    };
    for (int k = 1; k < count; ++k) {
      const glm::dvec2 point = sample_point(k, count);
      params.subpixel.s[0] = static_cast<float>(point.x);
      params.subpixel.s[1] = static_cast<float>(point.y);
      params.subpixel.s[2] = 1.0f;
      for (int first_row = band_first_row; first_row < end_row; first_row += dispatch.chunk_rows) {
        throw_if_cancelled();
        const int rows = std::min(dispatch.chunk_rows, end_row - first_row);
        const std::vector<cl_int> packets =
            packets_to_refine(refine, width, band_first_row, first_row, rows, dispatch, prepared.packets_per_item);
        if (packets.empty()) continue;
        dp.queue.enqueueWriteBuffer(refine_packets, CL_TRUE, 0, packets.size() * sizeof(cl_int), packets.data());
        params.first_row = first_row;
        kernel.setArg(0, sizeof(MarchParams), &params);
        cl::Event done;
        dp.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(packets.size() / prepared.packets_per_item),
                                      cl::NDRange(dispatch.local_items), nullptr, &done);
        const std::size_t floats = static_cast<std::size_t>(rows) * width;
        read_plane(CLMARCH_CHANNEL_DEPTH, floats, depth);
        if (color) {
          read_plane(CLMARCH_CHANNEL_R, floats, r);
          read_plane(CLMARCH_CHANNEL_G, floats, g);
          read_plane(CLMARCH_CHANNEL_B, floats, b);
        }
        {
          const BlockingCall uninterruptible_wait;
          dp.queue.finish();
        }
        kernel_ms += event_milliseconds(done);
        const std::size_t first = static_cast<std::size_t>(first_row - band_first_row) * width;
        for (std::size_t i = 0; i < floats; ++i) {
          if (!refine[first + i]) continue;  // not marched: the plane holds another pass's value
          sums.add(first + i, color ? glm::vec3(r[i], g[i], b[i]) : glm::vec3(0.0f), std::isfinite(depth[i]));
        }
      }
    }
  }
  sums.finish(buffers, count);
  return kernel_ms;
}

}  // namespace

RenderResult OpenClRenderer::render() {
  state_->cones_run = false;
  return render_rows(0, state_->render.height);
}

RenderResult OpenClRenderer::render_rows(int band_first_row, int band_rows) {
  State& s = *state_;
  DeviceProgram& dp = s.prepared.program;
  const int width = s.render.width;
  const int end_row = band_first_row + band_rows;
  const std::size_t pixels = static_cast<std::size_t>(width) * band_rows;
  static_assert(kBandRowAlignment % CLMARCH_COARSE_BLOCK == 0, "a band starts at a row of coarse blocks");
  if (band_first_row < 0 || band_rows <= 0 || end_row > s.render.height ||
      band_first_row % kBandRowAlignment != 0) {
    throw std::logic_error(fmt::format("render_rows: rows {} .. {} of an image of {} rows, not starting at a multiple of {}",
                                       band_first_row, end_row - 1, s.render.height, kBandRowAlignment));
  }
  // A band smaller than the whole image gets a dispatch of its own size (the output buffer, made
  // for the whole image's chunks, holds it); the parameters keep the whole image's camera and tiles.
  Dispatch dispatch = s.dispatch;
  MarchParams params = s.params;
  if (band_rows < s.render.height) {
    dispatch = plan_tile_dispatch(s.prepared, width, band_rows, s.dispatch.plane_stride);
    params.chunk_rows = dispatch.chunk_rows;
    params.plane_stride = static_cast<cl_int>(dispatch.plane_stride);
  }
  RenderResult result;
  result.buffers = FrameBuffers(width, band_rows);
  const std::size_t chunk_count = (static_cast<std::size_t>(band_rows) + dispatch.chunk_rows - 1) / dispatch.chunk_rows;
  ProgressLine progress("OpenCL chunks", static_cast<long long>(chunk_count),
                        static_cast<double>(pixels) / static_cast<double>(chunk_count));
  double kernel_ms = 0.0;
  std::uint64_t coarse_steps = 0;
  // PoCL compiles a kernel for its work-group size at its first enqueue, which for a large program
  // takes as long as the build: the first wait less the kernels' own time is counted as building.
  const auto enqueued = std::chrono::steady_clock::now();
  std::optional<double> first_enqueue_ms;
  with_device_errors(dp.device, [&] {
    std::optional<cl::Event> cones_done;
    if (s.cones && !s.cones_run) cones_done = enqueue_cone_pass(dp.queue, *s.cones, s.params);
    s.cones_run = true;
    // Planes the program does not write stay as FrameBuffers made them: 0.
    for_each_chunk(dp.queue, s.kernel, params, dispatch, band_first_row, end_row,
                   [&](int first_row, int rows, const cl::Event& done) {
      const std::size_t first = static_cast<std::size_t>(first_row - band_first_row) * width;
      const std::size_t count = static_cast<std::size_t>(rows) * width;
      for (int c : s.prepared.planes) {
        dp.queue.enqueueReadBuffer(s.out, CL_FALSE, c * dispatch.plane_stride * sizeof(float), count * sizeof(float),
                                   result.buffers.planes[c].data() + first);
      }
      {
        // The first chunk's wait holds PoCL's compile of the kernel for the work-group size, as
        // long as the build itself for a large scene.
        const BlockingCall uninterruptible_wait;
        dp.queue.finish();
      }
      kernel_ms += event_milliseconds(done);
      if (!first_enqueue_ms) {
        const double waited = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - enqueued).count();
        const double cones_ms = cones_done ? event_milliseconds(*cones_done) : 0.0;
        first_enqueue_ms = std::max(0.0, waited - kernel_ms - cones_ms);
      }
      progress.advance();
    });
    if (cones_done) {
      for (float steps : read_cone_plane(dp.queue, *s.cones, s.cones->steps)) coarse_steps += static_cast<std::uint64_t>(steps);
      kernel_ms += event_milliseconds(*cones_done);
    }
    if (s.sample_mask) {
      kernel_ms += refine_samples(s.render, s.prepared, s.kernel, s.out, *s.sample_mask, *s.refine_packets, params, dispatch,
                                  band_first_row, end_row, result.buffers);
    } else {
      set_single_sample_coverage(result.buffers);
    }
  });

  RenderStats& stats = result.stats;
  stats.device = dp.device.label();
  stats.lanes = s.prepared.lanes;
  if (!s.rendered) {
    stats.build_ms = dp.build_ms + first_enqueue_ms.value_or(0.0);
    log_verbose(fmt::format("first dispatch waited {:.0f} ms beyond its kernels (the driver's compile for the "
                            "work-group size), counted in build_ms", first_enqueue_ms.value_or(0.0)));
  }
  s.rendered = true;
  stats.kernel_ms = kernel_ms;
  stats.chunks = static_cast<int>(chunk_count);
  stats.steps = plane_total(result.buffers.plane(Channel::Steps));
  stats.wall_steps = plane_total(result.buffers.plane(Channel::WallSteps));
  stats.coarse_steps = coarse_steps;
  stats.rays_per_s = kernel_ms > 0.0 ? static_cast<double>(pixels) / (kernel_ms * 1e-3) : 0.0;
  return result;
}

RenderResult render_opencl(const Scene& scene, const OpenClOptions& options) { return OpenClRenderer(scene, options).render(); }

PointSamples eval_points_opencl(const Scene& scene, const std::vector<glm::dvec3>& points, const OpenClOptions& options) {
  PreparedProgram prepared = prepare_program(scene, options, KernelPurpose::EvalPoints);
  DeviceProgram& dp = prepared.program;
  const Dispatch dispatch = plan_point_dispatch(dp.device, points.size(), prepared.lanes);
  const std::size_t n = dispatch.plane_stride;
  std::vector<float> xs(n, 0.0f), ys(n, 0.0f), zs(n, 0.0f);
  for (std::size_t i = 0; i < points.size(); ++i) {
    xs[i] = static_cast<float>(points[i].x);
    ys[i] = static_cast<float>(points[i].y);
    zs[i] = static_cast<float>(points[i].z);
  }
  std::vector<std::vector<float>> outputs(5, std::vector<float>(n, 0.0f));
  with_device_errors(dp.device, [&] {
    const auto in_flags = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    cl::Buffer bx(dp.context, in_flags, n * sizeof(float), xs.data());
    cl::Buffer by(dp.context, in_flags, n * sizeof(float), ys.data());
    cl::Buffer bz(dp.context, in_flags, n * sizeof(float), zs.data());
    std::vector<cl::Buffer> out_buffers;
    cl::Kernel kernel(dp.program, "eval_points");
    kernel.setArg(0, bx);
    kernel.setArg(1, by);
    kernel.setArg(2, bz);
    for (int i = 0; i < 5; ++i) {
      out_buffers.emplace_back(dp.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
      kernel.setArg(3 + i, out_buffers.back());
    }
    // eval_points programs spell every literal; their values hold only an operand grid's data.
    const std::optional<cl::Buffer> values = make_scene_values(prepared, scene);
    set_scene_values_arg(kernel, 8, values);
    dp.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dispatch.global_items),
                                  cl::NDRange(dispatch.local_items));
    for (int i = 0; i < 5; ++i) dp.queue.enqueueReadBuffer(out_buffers[i], CL_TRUE, 0, n * sizeof(float), outputs[i].data());
  });
  PointSamples samples;
  samples.distance.assign(outputs[0].begin(), outputs[0].begin() + static_cast<std::ptrdiff_t>(points.size()));
  samples.color_distance.assign(outputs[1].begin(), outputs[1].begin() + static_cast<std::ptrdiff_t>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) samples.albedo.emplace_back(outputs[2][i], outputs[3][i], outputs[4][i]);
  return samples;
}

}  // namespace clmarch

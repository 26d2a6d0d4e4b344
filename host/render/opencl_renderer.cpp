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
#include "render/real_plane.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
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

/// (pixel, sample) pairs a refining dispatch marches at most (kernels/march.cl, sample_packet):
/// enough that PoCL's cost a dispatch is small beside them, few enough that the buffers stay small
/// (4 MiB of results, 16 with the shading's layers).
constexpr std::size_t kRefinePairs = std::size_t{1} << 18;

/// The refining pass's inputs and output besides the march's own (kernels/march.cl, refine_item).
struct AntialiasBuffers {
  /// A dispatch's pixels, by index in the band: at most kRefinePairs.
  cl::Buffer refine_pixels;
  /// The sample points of render.samples (sample_point), as floats: x, then y from
  /// CLMARCH_SAMPLE_POINT_STRIDE.
  cl::Buffer sample_points;
  /// Sums of colors and hits (and layers), at the first pair of each pixel in each packet:
  /// float4s float4s a pair (CLMARCH_REFINED_FLOAT4S).
  cl::Buffer refined_samples;
  int float4s = 1;
  bool layers = false;
};

struct OpenClRenderer::State {
  /// The scene's settings; not its tree, which the program holds (a million primitives' tree is
  /// hundreds of megabytes, and a copy of it set the process's peak memory).
  RenderSettings render;
  OpenClOptions options;
  /// The planes the program writes.
  MarchOutputs outputs;
  bool rendered = false;
  PreparedProgram prepared;
  Dispatch dispatch;
  MarchParams params;
  cl::Buffer out;
  cl::Buffer lights;
  std::optional<cl::Buffer> values;
  cl::Kernel kernel;
  std::optional<ConePass> cones;
  /// ANTIALIAS programs' refining pass.
  std::optional<AntialiasBuffers> antialias;
  /// Whether the coarse pass ran for the current scene (render_rows runs it at the first band).
  bool cones_run = false;
};

OpenClRenderer::OpenClRenderer(const Scene& scene, const OpenClOptions& options) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.render = scene.render;
  s.options = options;
  s.outputs = march_outputs(scene, options.purpose, options.ray_status);
  s.prepared = prepare_program(scene, options, options.purpose);
  DeviceProgram& dp = s.prepared.program;
  const std::size_t chunk_limit = options.max_chunk_pixels ? options.max_chunk_pixels : chunk_pixels_for(dp.device);
  s.dispatch = plan_tile_dispatch(s.prepared, scene.render.width, scene.render.height, chunk_limit);
  s.params = march_params(scene, s.dispatch);
  with_device_errors(dp.device, [&] {
    s.out = cl::Buffer(dp.context, CL_MEM_WRITE_ONLY | CL_MEM_HOST_READ_ONLY, march_output_bytes(s.dispatch));
    s.lights = make_light_buffer(dp.context, scene);
    s.values = make_scene_values(s.prepared, scene);
    s.kernel = cl::Kernel(dp.program, "march");
    s.cones = make_cone_pass(s.prepared, scene, s.values);
    const int next_arg = bind_march_inputs(s.kernel, s.out, s.lights, s.values, s.cones);
    if (uses_antialiasing(scene, options.purpose)) {
      static_assert(kMaxSamples + 16 <= CLMARCH_SAMPLE_POINT_STRIDE, "every sample point and a vector's lanes past it");
      const bool layers = s.outputs.layers;
      const int float4s = CLMARCH_REFINED_FLOAT4S(layers);
      s.antialias = AntialiasBuffers{
          cl::Buffer(dp.context, CL_MEM_READ_ONLY, kRefinePairs * sizeof(cl_int)),
          cl::Buffer(dp.context, CL_MEM_READ_ONLY, std::size_t{2} * CLMARCH_SAMPLE_POINT_STRIDE * sizeof(float)),
          cl::Buffer(dp.context, CL_MEM_WRITE_ONLY, kRefinePairs * float4s * sizeof(cl_float4)), float4s, layers};
      s.kernel.setArg(next_arg, s.antialias->refine_pixels);
      s.kernel.setArg(next_arg + 1, s.antialias->sample_points);
      s.kernel.setArg(next_arg + 2, s.antialias->refined_samples);
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
      options.value_slots != mine.value_slots || options.ray_status != mine.ray_status ||
      options.literals_in_buffer != mine.literals_in_buffer ||
      !(scene_variant(scene, options.variant) == s.prepared.kernel_options.variant)) {
    return false;
  }
  // A scene that wants its numbers spelled (render.literals: inline) is not rendered by a program
  // that reads them, nor the other way round, though the key of the open code is the same.
  if (literals_in_buffer(scene, s.prepared.kernel_options, options.literals_in_buffer) != s.prepared.literals_in_buffer)
    return false;
  return program_key(scene, s.prepared.kernel_options) == s.prepared.key;
}

void OpenClRenderer::set_scene(const Scene& scene) {
  State& s = *state_;
  s.render = scene.render;
  s.cones_run = false;
  s.params = march_params(scene, s.dispatch);
  with_device_errors(s.prepared.program.device, [&] {
    const DeviceProgram& dp = s.prepared.program;
    write_lights(dp.queue, dp.context, scene, s.lights);
    write_scene_values(s.prepared, scene, s.values);
    // Either may have moved to a larger buffer: the kernels must not keep the old one.
    bind_march_inputs(s.kernel, s.out, s.lights, s.values, s.cones);
    if (s.cones) set_scene_values_arg(s.cones->kernel, 3, s.values);
  });
}

const std::string& OpenClRenderer::source() const { return state_->prepared.source; }

namespace {

/// The refining pass of an anti-aliased render of rows band_first_row .. end_row - 1, whose centre
/// rays are in buffers: samples 1 .. N - 1 of the pixels pixels_to_refine flags, a (pixel, sample)
/// pair a lane (kernels/march.cl, sample_packet), at most kRefinePairs a dispatch; their means are
/// written into buffers. Returns its kernel time.
double refine_samples(const RenderSettings& render, PreparedProgram& prepared, cl::Kernel& kernel,
                      const AntialiasBuffers& antialias, MarchParams params, const Dispatch& dispatch,
                      int band_first_row, int end_row, FrameBuffers& buffers) {
  const int count = render.samples;
  SampleSums sums(buffers, pixels_to_refine(buffers, render.adaptive), antialias.layers);
  const std::vector<std::uint8_t>& refine = sums.refine();
  DeviceProgram& dp = prepared.program;
  std::vector<float> points(std::size_t{2} * CLMARCH_SAMPLE_POINT_STRIDE, 0.0f);
  for (int k = 0; k < count; ++k) {
    const glm::dvec2 point = sample_point(k, count);
    points[k] = static_cast<float>(point.x);
    points[CLMARCH_SAMPLE_POINT_STRIDE + k] = static_cast<float>(point.y);
  }
  dp.queue.enqueueWriteBuffer(antialias.sample_points, CL_TRUE, 0, points.size() * sizeof(float), points.data());
  params.first_row = band_first_row;
  params.sampling.s[0] = 1.0f;
  params.sampling.s[1] = static_cast<float>(count);

  const std::size_t per_pixel = static_cast<std::size_t>(count - 1);
  const std::size_t batch_pixels = std::max<std::size_t>(1, kRefinePairs / per_pixel);
  const std::size_t lanes = static_cast<std::size_t>(prepared.lanes);
  std::vector<cl_int> pixels;
  pixels.reserve(batch_pixels);
  const std::size_t float4s = static_cast<std::size_t>(antialias.float4s);
  std::vector<cl_float4> samples(batch_pixels * per_pixel * float4s);
  std::vector<float> values(sums.values_per_sample());
  double kernel_ms = 0.0;
  const auto run_batch = [&] {
    throw_if_cancelled();
    const std::size_t pairs = pixels.size() * per_pixel;
    params.sampling.s[2] = static_cast<float>(pixels.size());
    kernel.setArg(0, sizeof(MarchParams), &params);
    dp.queue.enqueueWriteBuffer(antialias.refine_pixels, CL_TRUE, 0, pixels.size() * sizeof(cl_int), pixels.data());
    const std::size_t packets = (pairs + lanes - 1) / lanes;
    const std::size_t items = (packets + prepared.packets_per_item - 1) / prepared.packets_per_item;
    const std::size_t global = (items + dispatch.local_items - 1) / dispatch.local_items * dispatch.local_items;
    cl::Event done;
    dp.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(dispatch.local_items),
                                  nullptr, &done);
    dp.queue.enqueueReadBuffer(antialias.refined_samples, CL_FALSE, 0, pairs * float4s * sizeof(cl_float4),
                               samples.data());
    {
      const BlockingCall uninterruptible_wait;
      dp.queue.finish();
    }
    kernel_ms += event_milliseconds(done);
    // A packet's sums of one pixel lie at the first of its pairs there (kernels/march.cl,
    // store_samples): color and hits, then each layer's r, g, b (and a 0).
    for (std::size_t pair = 0; pair < pairs; ++pair) {
      if (pair % lanes != 0 && pair % per_pixel != 0) continue;
      const cl_float4* sum = &samples[pair * float4s];
      std::copy(sum[0].s, sum[0].s + 4, values.begin());
      for (std::size_t layer = 1; layer < float4s; ++layer)
        std::copy(sum[layer].s, sum[layer].s + 3, values.begin() + static_cast<std::ptrdiff_t>(1 + 3 * layer));
      sums.add(static_cast<std::size_t>(pixels[pair / per_pixel]), values.data());
    }
    pixels.clear();
  };
  const std::size_t band_pixels = static_cast<std::size_t>(end_row - band_first_row) * buffers.width;
  for (std::size_t i = 0; i < band_pixels; ++i) {
    if (!refine[i]) continue;
    pixels.push_back(static_cast<cl_int>(i));
    if (pixels.size() == batch_pixels) run_batch();
  }
  if (!pixels.empty()) run_batch();
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
  if (band_first_row < 0 || band_rows <= 0 || end_row > s.render.height || band_first_row % kBandRowAlignment != 0) {
    throw std::logic_error(
        fmt::format("render_rows: rows {} .. {} of an image of {} rows, not starting at a multiple of {}",
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
  result.buffers.has_ids = s.outputs.ids;
  result.buffers.has_layers = s.outputs.layers;
  result.buffers.has_depth_lo = s.outputs.depth_lo;
  result.buffers.has_status = s.outputs.status;
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
    for_each_chunk(
        dp.queue, s.kernel, params, dispatch, band_first_row, end_row,
        [&](int first_row, int rows, const cl::Event& done) {
          const std::size_t first = static_cast<std::size_t>(first_row - band_first_row) * width;
          const std::size_t count = static_cast<std::size_t>(rows) * width;
          for (int c : s.prepared.planes) {
            dp.queue.enqueueReadBuffer(s.out, CL_FALSE, c * dispatch.plane_stride * sizeof(float),
                                       count * sizeof(float), result.buffers.planes[c].data() + first);
          }
          {
            // The first chunk's wait holds PoCL's compile of the kernel for the work-group size, as
            // long as the build itself for a large scene.
            const BlockingCall uninterruptible_wait;
            dp.queue.finish();
          }
          kernel_ms += event_milliseconds(done);
          if (!first_enqueue_ms) {
            const double waited =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - enqueued).count();
            const double cones_ms = cones_done ? event_milliseconds(*cones_done) : 0.0;
            first_enqueue_ms = std::max(0.0, waited - kernel_ms - cones_ms);
          }
          progress.advance();
        });
    if (cones_done) {
      for (float steps : read_cone_plane(dp.queue, *s.cones, s.cones->steps))
        coarse_steps += static_cast<std::uint64_t>(steps);
      kernel_ms += event_milliseconds(*cones_done);
    }
    if (s.antialias) {
      kernel_ms += refine_samples(s.render, s.prepared, s.kernel, *s.antialias, params, dispatch, band_first_row,
                                  end_row, result.buffers);
    } else {
      set_single_sample_coverage(result.buffers);
    }
  });

  RenderStats& stats = result.stats;
  stats.device = dp.device.label();
  stats.lanes = s.prepared.lanes;
  stats.precision = s.prepared.kernel_options.variant.precision;
  stats.literals = s.prepared.literals_in_buffer ? "buffer" : "inline";
  stats.stages = s.prepared.stages_called ? "called" : "inline";
  if (!s.rendered) {
    stats.build_ms = dp.build_ms + first_enqueue_ms.value_or(0.0);
    log_verbose(
        fmt::format("first dispatch waited {:.0f} ms beyond its kernels (the driver's compile for the "
                    "work-group size), counted in build_ms",
                    first_enqueue_ms.value_or(0.0)));
  }
  s.rendered = true;
  stats.kernel_ms = kernel_ms;
  stats.chunks = static_cast<int>(chunk_count);
  stats.steps = plane_total(result.buffers.plane(Channel::Steps));
  stats.wall_steps = plane_total(result.buffers.plane(Channel::WallSteps));
  stats.coarse_steps = coarse_steps;
  if (result.buffers.has_status) {
    stats.out_of_steps = result.buffers.rays_with_status(RayStatus::OutOfSteps);
    stats.out_of_distance = result.buffers.rays_with_status(RayStatus::OutOfDistance);
  }
  stats.rays_per_s = kernel_ms > 0.0 ? static_cast<double>(pixels) / (kernel_ms * 1e-3) : 0.0;
  return result;
}

RenderResult render_opencl(const Scene& scene, const OpenClOptions& options) {
  return OpenClRenderer(scene, options).render();
}

PointSamples eval_points_opencl(const Scene& scene, const std::vector<glm::dvec3>& points, const OpenClOptions& options,
                                const glm::dvec3& origin) {
  PreparedProgram prepared = prepare_program(scene, options, KernelPurpose::EvalPoints);
  DeviceProgram& dp = prepared.program;
  const Dispatch dispatch = plan_point_dispatch(dp.device, points.size(), prepared.lanes);
  const std::size_t n = dispatch.plane_stride;
  const bool in_double = prepared.kernel_options.variant.precision == Precision::Double;
  std::vector<RealPlane> coordinates = coordinate_planes(points, n, in_double);
  // distance and color distance in the program's real, then albedo r, g, b and the primitive number.
  std::vector<RealPlane> distances(2, RealPlane(n, in_double));
  constexpr int kFloatOutputs = 4;
  std::vector<std::vector<float>> outputs(kFloatOutputs, std::vector<float>(n, 0.0f));
  with_device_errors(dp.device, [&] {
    const auto in_flags = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    cl::Kernel kernel(dp.program, "eval_points");
    // The buffers live until the kernel is done: an argument does not hold its buffer.
    std::vector<cl::Buffer> buffers;
    for (RealPlane& plane : coordinates) buffers.emplace_back(dp.context, in_flags, plane.size_bytes(), plane.data());
    for (const RealPlane& plane : distances) buffers.emplace_back(dp.context, CL_MEM_WRITE_ONLY, plane.size_bytes());
    for (int i = 0; i < kFloatOutputs; ++i) buffers.emplace_back(dp.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
    for (std::size_t i = 0; i < buffers.size(); ++i) kernel.setArg(static_cast<cl_uint>(i), buffers[i]);
    const auto after_buffers = static_cast<cl_uint>(buffers.size());
    // eval_points programs spell every literal; their values hold only an operand grid's data.
    const std::optional<cl::Buffer> values = make_scene_values(prepared, scene);
    set_scene_values_arg(kernel, after_buffers, values);
    // origin = hi + lo, each a float: the double program adds them in double.
    const glm::vec3 hi(origin);
    const glm::vec3 lo(origin - glm::dvec3(hi));
    kernel.setArg(after_buffers + 1, cl_float4{{hi.x, hi.y, hi.z, 0.0f}});
    kernel.setArg(after_buffers + 2, cl_float4{{lo.x, lo.y, lo.z, 0.0f}});
    dp.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dispatch.global_items),
                                  cl::NDRange(dispatch.local_items));
    for (std::size_t k = 0; k < distances.size(); ++k)
      dp.queue.enqueueReadBuffer(buffers[3 + k], CL_TRUE, 0, distances[k].size_bytes(), distances[k].data());
    for (int i = 0; i < kFloatOutputs; ++i)
      dp.queue.enqueueReadBuffer(buffers[5 + static_cast<std::size_t>(i)], CL_TRUE, 0, n * sizeof(float),
                                 outputs[i].data());
  });
  PointSamples samples;
  for (std::size_t i = 0; i < points.size(); ++i) {
    samples.distance.push_back(distances[0].get(i));
    samples.color_distance.push_back(distances[1].get(i));
    samples.albedo.emplace_back(outputs[0][i], outputs[1][i], outputs[2][i]);
    samples.primitive.push_back(outputs[3][i]);
  }
  return samples;
}

}  // namespace clmarch

// Repeated renders and the throughput ceiling: record the march's points, then replay them.
#include "bench/throughput.hpp"

#include "cl/cl_errors.hpp"
#include "codegen/kernel_source.hpp"
#include "render/cone_pass.hpp"
#include "render/device_inputs.hpp"
#include "render/dispatch_plan.hpp"
#include "render/prepared_program.hpp"

#include <algorithm>
#include <numeric>

namespace clmarch {
namespace {

/// Marches the scene's camera rays with the Ceiling program: each pixel's k-th evaluated point is
/// stored at sample_base[pixel] + k of the x, y, z planes of samples (stride floats apart), and
/// nothing for a base of -1. values: the program's values buffer. Returns the steps of every pixel.
std::vector<int> record_march(const Scene& scene, PreparedProgram& prepared, const std::optional<cl::Buffer>& values,
                              const std::vector<cl_int>& sample_base, cl::Buffer* samples, std::size_t stride) {
  DeviceProgram& dp = prepared.program;
  const int width = scene.render.width, height = scene.render.height;
  const Dispatch dispatch = plan_tile_dispatch(prepared, width, height, chunk_pixels_for(dp.device));
  std::vector<float> steps(static_cast<std::size_t>(width) * height);
  cl::Buffer out(dp.context, CL_MEM_WRITE_ONLY | CL_MEM_HOST_READ_ONLY, march_output_bytes(dispatch));
  cl::Buffer light_buffer = make_light_buffer(dp.context, scene);
  cl::Buffer bases(dp.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sample_base.size() * sizeof(cl_int),
                   const_cast<cl_int*>(sample_base.data()));
  cl::Kernel kernel(dp.program, "march");
  std::optional<ConePass> cones = make_cone_pass(prepared, scene, values);
  const int record_arg = bind_march_inputs(kernel, out, light_buffer, values, cones);
  kernel.setArg(record_arg, bases);
  if (samples) {
    kernel.setArg(record_arg + 1, *samples);
  } else {
    kernel.setArg(record_arg + 1, sizeof(cl_mem), nullptr);  // a NULL pointer: the march records nothing
  }
  kernel.setArg(record_arg + 2, static_cast<cl_int>(stride));
  const MarchParams params = march_params(scene, dispatch);
  if (cones) enqueue_cone_pass(dp.queue, *cones, params);
  for_each_chunk(dp.queue, kernel, params, dispatch, height, [&](int first_row, int rows, const cl::Event&) {
    dp.queue.enqueueReadBuffer(out, CL_TRUE, CLMARCH_CHANNEL_STEPS * dispatch.plane_stride * sizeof(float),
                               static_cast<std::size_t>(rows) * width * sizeof(float),
                               steps.data() + static_cast<std::size_t>(first_row) * width);
  });
  return std::vector<int>(steps.begin(), steps.end());
}

}  // namespace

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

double lane_use(const std::vector<float>& steps, int width, int height, int lanes) {
  const int tile_width = packet_width(lanes), tile_height = packet_height(lanes);
  double used = 0.0, executed = 0.0;
  for (int y0 = 0; y0 < height; y0 += tile_height) {
    for (int x0 = 0; x0 < width; x0 += tile_width) {
      float slowest = 0.0f;
      for (int y = y0; y < std::min(y0 + tile_height, height); ++y) {
        for (int x = x0; x < std::min(x0 + tile_width, width); ++x) {
          const float s = steps[static_cast<std::size_t>(y) * width + x];
          used += s;
          slowest = std::max(slowest, s);
        }
      }
      executed += static_cast<double>(slowest) * lanes;
    }
  }
  return executed > 0.0 ? used / executed : 1.0;
}

CeilingKernel::CeilingKernel(const Scene& scene, const OpenClOptions& options, int repeats, std::uint64_t max_samples)
    : repeats_(repeats) {
  prepared_ = prepare_program(scene, options, KernelPurpose::Ceiling);
  DeviceProgram& program = prepared_.program;
  with_device_errors(program.device, [&] {
    // First the steps of every pixel (recording nothing), then each kept pixel's points at offsets
    // from the running sum of its steps. Both marches run the same program, so they take the same steps.
    const std::size_t pixels = static_cast<std::size_t>(scene.render.width) * scene.render.height;
    std::vector<cl_int> sample_base(pixels, -1);
    // Benchmark programs spell every literal (no value slots): the values hold an operand grid's
    // data, or are NULL without one.
    values_ = make_scene_values(prepared_, scene);
    const std::vector<int> steps = record_march(scene, prepared_, values_, sample_base, nullptr, 0);
    marched_steps_ = std::accumulate(steps.begin(), steps.end(), std::uint64_t{0});
    pixel_stride_ = std::max<std::uint64_t>(1, (marched_steps_ + max_samples - 1) / max_samples);
    for (std::size_t pixel = 0; pixel < pixels; pixel += pixel_stride_) {
      sample_base[pixel] = static_cast<cl_int>(samples_);
      samples_ += static_cast<std::uint64_t>(steps[pixel]);
    }
    const Dispatch replay = plan_point_dispatch(program.device, std::max<std::uint64_t>(samples_, 1), prepared_.lanes);
    global_items_ = replay.global_items;
    local_items_ = replay.local_items;
    plane_ = replay.plane_stride;
    // Padding points past samples_ stay 0: the replay evaluates them in lanes it does not count.
    const std::size_t bytes = 3 * plane_ * sizeof(float);
    samples_buffer_ = cl::Buffer(program.context, CL_MEM_READ_WRITE, bytes);
    program.queue.enqueueFillBuffer(samples_buffer_, 0.0f, 0, bytes);
    record_march(scene, prepared_, values_, sample_base, &samples_buffer_, plane_);

    kernel_ = cl::Kernel(program.program, "replay_samples");
    sums_ = cl::Buffer(program.context, CL_MEM_WRITE_ONLY, plane_ * sizeof(float));
    evaluations_ = cl::Buffer(program.context, CL_MEM_WRITE_ONLY, plane_ * sizeof(cl_int));
    kernel_.setArg(0, samples_buffer_);
    kernel_.setArg(1, static_cast<cl_int>(samples_));
    kernel_.setArg(2, static_cast<cl_int>(plane_));
    kernel_.setArg(3, static_cast<cl_int>(repeats_));
    kernel_.setArg(4, sums_);
    kernel_.setArg(5, evaluations_);
    set_scene_values_arg(kernel_, 6, values_);
  });
}

std::vector<glm::vec3> CeilingKernel::read_samples() {
  std::vector<float> planes(3 * plane_);
  with_device_errors(prepared_.program.device, [&] {
    prepared_.program.queue.enqueueReadBuffer(samples_buffer_, CL_TRUE, 0, planes.size() * sizeof(float),
                                              planes.data());
  });
  std::vector<glm::vec3> points(samples_);
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = {planes[i], planes[plane_ + i], planes[2 * plane_ + i]};
  return points;
}

double CeilingKernel::run_ms() {
  return with_device_errors(prepared_.program.device, [&] {
    cl::Event done;
    prepared_.program.queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(global_items_),
                                                 cl::NDRange(local_items_), nullptr, &done);
    std::vector<cl_int> counts(plane_);
    prepared_.program.queue.enqueueReadBuffer(evaluations_, CL_TRUE, 0, plane_ * sizeof(cl_int), counts.data());
    counted_ = std::accumulate(counts.begin(), counts.end(), std::uint64_t{0},
                               [](std::uint64_t sum, cl_int c) { return sum + static_cast<std::uint64_t>(c); });
    return event_milliseconds(done);
  });
}

std::size_t depth_frame_floats(const Scene& scene) {
  return march_outputs(scene, KernelPurpose::DepthSteps, false).planes().size() * scene.render.width *
         scene.render.height;
}

OutputFloorKernel::OutputFloorKernel(const OpenClOptions& options, std::size_t floats)
    : program_(build_device_program(select_device(options.device), output_floor_source())),
      floats_((std::max<std::size_t>(floats, 1) + 15) / 16 * 16) {
  with_device_errors(program_.device, [&] {
    planes_ = cl::Buffer(program_.context, CL_MEM_WRITE_ONLY, floats_ * sizeof(float));
    kernel_ = cl::Kernel(program_.program, "fill_planes");
    kernel_.setArg(0, planes_);
  });
}

double OutputFloorKernel::run_ms() {
  return with_device_errors(program_.device, [&] {
    value_ += 1.0f;
    kernel_.setArg(1, value_);
    cl::Event done;
    // The driver picks the work-group size: the floor is the fastest store, not the march's shape.
    program_.queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(floats_ / 16), cl::NullRange, nullptr,
                                        &done);
    done.wait();
    return event_milliseconds(done);
  });
}

std::vector<float> OutputFloorKernel::read_back() {
  std::vector<float> values(floats_);
  with_device_errors(program_.device, [&] {
    program_.queue.enqueueReadBuffer(planes_, CL_TRUE, 0, floats_ * sizeof(float), values.data());
  });
  return values;
}

}  // namespace clmarch

// The OpenCL render path. Buffers are planar (one plane per channel) and padded to whole packets,
// so every work-item stores full vectors.
#include "render/opencl_renderer.hpp"

#include "cl/cl_errors.hpp"
#include "cl/device_program.hpp"
#include "common/cancellation.hpp"
#include "common/progress.hpp"
#include "device_types.h"
#include "image/atomic_file.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/tiling_model.hpp"

#include <algorithm>
#include <numeric>

namespace clmarch {
namespace {

cl_float4 to_cl(const glm::dvec3& v) {
  cl_float4 out;
  out.s[0] = static_cast<float>(v.x);
  out.s[1] = static_cast<float>(v.y);
  out.s[2] = static_cast<float>(v.z);
  out.s[3] = 0.0f;
  return out;
}

/// Work-items per work-group: GPUs want many; PoCL loops over the items of a group on one core, and
/// one fixed size keeps its per-size compile of the work-group function cached.
std::size_t local_size(const DeviceEntry& device) { return device.is_gpu ? 64 : 8; }

struct Dispatch {
  std::size_t global_items = 0;
  std::size_t local_items = 0;
  /// Floats per plane: global_items * lanes.
  std::size_t plane_stride = 0;
};

Dispatch plan_dispatch(const DeviceEntry& device, std::size_t count, int lanes) {
  Dispatch d;
  d.local_items = local_size(device);
  const std::size_t items = (count + lanes - 1) / lanes;
  d.global_items = (items + d.local_items - 1) / d.local_items * d.local_items;
  d.plane_stride = d.global_items * lanes;
  return d;
}

/// Pixels per dispatch: the output buffer must fit the device's largest allocation and a quarter
/// of its memory; 4 M pixels at most so that progress and cancellation come often.
std::size_t chunk_pixels_for(const DeviceEntry& device) {
  constexpr std::size_t kResponsiveChunk = std::size_t{1} << 22;
  const std::size_t bytes_per_pixel = CLMARCH_CHANNEL_COUNT * sizeof(float);
  const std::size_t max_alloc = device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  const std::size_t global = device.device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>() / 4;
  return std::max<std::size_t>(1, std::min({kResponsiveChunk, max_alloc / bytes_per_pixel, global / bytes_per_pixel}));
}

/// Lights as the kernel reads them (kernels/shading.cl): positions relative to the camera.
std::vector<cl_float4> light_data(const Scene& scene) {
  std::vector<cl_float4> data;
  for (const Light& light : scene.lights) {
    cl_float4 where = light.kind == LightKind::Point ? to_cl(light.position - scene.camera.position) : to_cl(light.direction);
    where.s[3] = light.kind == LightKind::Point ? 1.0f : 0.0f;
    data.push_back(where);
    data.push_back(to_cl(light.color * light.intensity));
  }
  if (data.empty()) data.push_back(to_cl(glm::dvec3(0.0)));  // a buffer may not be empty
  return data;
}

std::uint64_t plane_total(const std::vector<float>& plane) {
  return std::accumulate(plane.begin(), plane.end(), std::uint64_t{0},
                         [](std::uint64_t sum, float s) { return sum + static_cast<std::uint64_t>(s); });
}

struct PreparedProgram {
  DeviceProgram program;
  int lanes = 1;
};

PreparedProgram prepare(const Scene& scene, const OpenClOptions& options, KernelPurpose purpose) {
  const DeviceEntry device = select_device(options.device);
  KernelOptions kernel_options;
  kernel_options.purpose = purpose;
  kernel_options.lanes = options.lanes.value_or(default_lanes(device));
  kernel_options.variant = options.variant;
  const std::string source = generate_kernel_source(scene, kernel_options);
  if (!options.dump_kernel_path.empty()) write_file_atomically(options.dump_kernel_path, source);
  return {build_device_program(device, source, kernel_build_options(options.variant)), kernel_options.lanes};
}

}  // namespace

RenderResult render_opencl(const Scene& scene, const OpenClOptions& options) {
  PreparedProgram prepared = prepare(scene, options, options.purpose);
  DeviceProgram& dp = prepared.program;
  const int width = scene.render.width;
  const int height = scene.render.height;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  const std::size_t chunk_limit = options.max_chunk_pixels ? options.max_chunk_pixels : chunk_pixels_for(dp.device);
  const Dispatch dispatch = plan_dispatch(dp.device, std::min(pixels, chunk_limit), prepared.lanes);

  const CameraBasis basis = camera_basis(scene.camera, width, height);
  MarchParams params{};
  params.origin = to_cl(basis.origin - map_frame_origin(scene));
  params.forward = to_cl(basis.forward);
  params.right_extent = to_cl(basis.right_extent);
  params.up_extent = to_cl(basis.up_extent);
  params.width = width;
  params.height = height;
  params.pixel_count = static_cast<cl_int>(pixels);
  params.plane_stride = static_cast<cl_int>(dispatch.plane_stride);
  params.max_steps = scene.render.max_steps;
  params.epsilon = static_cast<float>(scene.render.epsilon);
  params.max_distance = static_cast<float>(scene.render.max_distance);
  params.normal_epsilon = static_cast<float>(scene.render.normal_epsilon);
  if (scene.tiling) params.origin_in_cell = to_cl(offset_in_cell(scene.camera.position, scene.tiling->cell));
  params.camera_height = static_cast<float>(scene.camera.position.y);
  params.over_relaxation = static_cast<float>(scene.render.over_relaxation);
  params.hit_cone_slope = static_cast<float>(hit_cone_slope(scene.render, scene.camera));
  if (const std::optional<BoundingSphere> bounds = camera_ray_bounds(scene)) {
    params.bounds = to_cl(scene.camera.position - bounds->center);
    params.bounds.s[3] = static_cast<float>(bounds->radius);
  }
  const std::vector<cl_float4> lights = light_data(scene);

  RenderResult result;
  result.buffers = FrameBuffers(width, height);
  const std::size_t chunk_pixels = dispatch.plane_stride;
  const std::size_t chunk_count = (pixels + chunk_pixels - 1) / chunk_pixels;
  ProgressLine progress("OpenCL chunks", static_cast<long long>(chunk_count),
                        static_cast<double>(pixels) / static_cast<double>(chunk_count));
  double kernel_ms = 0.0;
  with_device_errors(dp.device, [&] {
    const std::size_t bytes = dispatch.plane_stride * CLMARCH_CHANNEL_COUNT * sizeof(float);
    cl::Buffer out(dp.context, CL_MEM_WRITE_ONLY | CL_MEM_HOST_READ_ONLY, bytes);
    // Planes the kernel does not write (no shading, no normals) must read back as zeros.
    dp.queue.enqueueFillBuffer(out, 0.0f, 0, bytes);
    cl::Buffer light_buffer(dp.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lights.size() * sizeof(cl_float4),
                            const_cast<cl_float4*>(lights.data()));
    cl::Kernel kernel(dp.program, "march");
    kernel.setArg(1, out);
    kernel.setArg(2, light_buffer);
    for (std::size_t first = 0; first < pixels; first += chunk_pixels) {
      throw_if_cancelled();
      const std::size_t count = std::min(chunk_pixels, pixels - first);
      params.first_pixel = static_cast<cl_int>(first);
      kernel.setArg(0, sizeof(MarchParams), &params);
      cl::Event done;
      dp.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dispatch.global_items),
                                    cl::NDRange(dispatch.local_items), nullptr, &done);
      for (int c = 0; c < kChannelCount; ++c) {
        dp.queue.enqueueReadBuffer(out, CL_FALSE, c * dispatch.plane_stride * sizeof(float), count * sizeof(float),
                                   result.buffers.planes[c].data() + first);
      }
      dp.queue.finish();
      kernel_ms += event_milliseconds(done);
      progress.advance();
    }
  });

  RenderStats& stats = result.stats;
  stats.device = dp.device.label();
  stats.lanes = prepared.lanes;
  stats.build_ms = dp.build_ms;
  stats.kernel_ms = kernel_ms;
  stats.chunks = static_cast<int>(chunk_count);
  stats.steps = plane_total(result.buffers.plane(Channel::Steps));
  stats.wall_steps = plane_total(result.buffers.plane(Channel::WallSteps));
  stats.rays_per_s = kernel_ms > 0.0 ? static_cast<double>(pixels) / (kernel_ms * 1e-3) : 0.0;
  return result;
}

PointSamples eval_points_opencl(const Scene& scene, const std::vector<glm::dvec3>& points, const OpenClOptions& options) {
  PreparedProgram prepared = prepare(scene, options, KernelPurpose::EvalPoints);
  DeviceProgram& dp = prepared.program;
  const Dispatch dispatch = plan_dispatch(dp.device, points.size(), prepared.lanes);
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

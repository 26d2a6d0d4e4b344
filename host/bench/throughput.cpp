// Repeated renders and the throughput ceiling kernel.
#include "bench/throughput.hpp"

#include "cl/cl_errors.hpp"
#include "codegen/kernel_source.hpp"
#include "scene/camera_model.hpp"

#include <algorithm>
#include <numeric>

namespace clmarch {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

std::vector<double> time_renders(const Scene& scene, const OpenClOptions& options, int repeat, RenderResult* last) {
  RenderResult result = render_opencl(scene, options);
  std::vector<double> ms;
  for (int i = 0; i < repeat; ++i) {
    result = render_opencl(scene, options);
    ms.push_back(result.stats.kernel_ms);
  }
  if (last) *last = std::move(result);
  return ms;
}

CeilingKernel::CeilingKernel(const Scene& scene, const OpenClOptions& options, int depths_per_ray) : depths_(depths_per_ray) {
  const DeviceEntry device = select_device(options.device);
  lanes_ = options.lanes.value_or(default_lanes(device));
  program_ = build_device_program(device, generate_kernel_source(scene, {KernelPurpose::EvalPoints, lanes_, options.variant}),
                                  kernel_build_options(options.variant));

  const int width = scene.render.width, height = scene.render.height;
  rays_ = static_cast<std::uint64_t>(width) * height;
  local_items_ = default_local_size(device);
  const std::size_t items = (rays_ + lanes_ - 1) / lanes_;
  global_items_ = (items + local_items_ - 1) / local_items_ * local_items_;
  plane_ = global_items_ * lanes_;

  // Rays of the image through the camera contract; the depths span the region around look_at.
  const CameraBasis basis = camera_basis(scene.camera, width, height);
  const double span = 2.0 * glm::length(scene.camera.look_at - scene.camera.position);
  const double spacing = span / depths_;
  std::vector<std::vector<float>> planes(6, std::vector<float>(plane_, 0.0f));
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const std::size_t at = static_cast<std::size_t>(j) * width + i;
      const glm::dvec3 step = pixel_ray_direction(basis, i, j) * spacing;
      for (int a = 0; a < 3; ++a) {
        planes[a][at] = static_cast<float>(basis.origin[a]);
        planes[3 + a][at] = static_cast<float>(step[a]);
      }
    }
  }
  with_device_errors(program_.device, [&] {
    kernel_ = cl::Kernel(program_.program, "eval_ceiling");
    for (int a = 0; a < 6; ++a) {
      inputs_.emplace_back(program_.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, plane_ * sizeof(float), planes[a].data());
      kernel_.setArg(a, inputs_.back());
    }
    sums_ = cl::Buffer(program_.context, CL_MEM_WRITE_ONLY, plane_ * sizeof(float));
    evaluations_ = cl::Buffer(program_.context, CL_MEM_WRITE_ONLY, plane_ * sizeof(cl_int));
    kernel_.setArg(6, static_cast<cl_int>(rays_));
    kernel_.setArg(7, static_cast<cl_int>(depths_));
    kernel_.setArg(8, sums_);
    kernel_.setArg(9, evaluations_);
  });
}

double CeilingKernel::run_ms() {
  return with_device_errors(program_.device, [&] {
    cl::Event done;
    program_.queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(global_items_), cl::NDRange(local_items_),
                                        nullptr, &done);
    std::vector<cl_int> counts(plane_);
    program_.queue.enqueueReadBuffer(evaluations_, CL_TRUE, 0, plane_ * sizeof(cl_int), counts.data());
    counted_ = std::accumulate(counts.begin(), counts.end(), std::uint64_t{0},
                               [](std::uint64_t sum, cl_int c) { return sum + static_cast<std::uint64_t>(c); });
    return event_milliseconds(done);
  });
}

}  // namespace clmarch

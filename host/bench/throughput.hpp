// Measuring blocks of the benchmarks: kernel times of repeated OpenCL renders, and the throughput
// ceiling of a scene's distance function (the eval_ceiling kernel of kernels/eval_points.cl).
#pragma once

#include "cl/device_program.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <vector>

namespace clmarch {

/// The median of values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

/// Kernel milliseconds (from profiling events) of repeat renders of scene with options, after one
/// render that is not counted (it pays the program build and PoCL's work-group compile). The
/// last render's result is kept in last when given.
std::vector<double> time_renders(const Scene& scene, const OpenClOptions& options, int repeat, RenderResult* last = nullptr);

/// The scene's map() evaluated on a dense batch of points with no divergence: at depths_per_ray
/// evenly spaced depths along each camera ray of the scene's image (out to twice the distance from
/// the camera to look_at), LANES rays per work-item as in the march kernel. Built once, run often.
class CeilingKernel {
 public:
  CeilingKernel(const Scene& scene, const OpenClOptions& options, int depths_per_ray);
  /// Runs the kernel once; returns its milliseconds from the profiling event.
  double run_ms();
  /// Points of one run: rays * depths_per_ray.
  std::uint64_t points() const { return rays_ * static_cast<std::uint64_t>(depths_); }
  /// Evaluations the kernel counted in the last run (equal to points()).
  std::uint64_t counted_evaluations() const { return counted_; }
  int lanes() const { return lanes_; }
  const DeviceProgram& program() const { return program_; }

 private:
  DeviceProgram program_;
  int lanes_ = 1;
  std::uint64_t rays_ = 0;
  int depths_ = 0;
  std::size_t global_items_ = 0;
  std::size_t local_items_ = 0;
  std::size_t plane_ = 0;
  cl::Kernel kernel_;
  cl::Buffer sums_;
  cl::Buffer evaluations_;
  std::vector<cl::Buffer> inputs_;
  std::uint64_t counted_ = 0;
};

}  // namespace clmarch

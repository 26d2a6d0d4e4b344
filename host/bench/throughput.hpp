// Measuring blocks of the benchmarks: medians, lane use, the throughput ceiling of a scene's
// distance function (the replay_samples kernel of kernels/replay.cl) and the output floor.
#pragma once

#include "cl/device_program.hpp"
#include "render/opencl_renderer.hpp"
#include "render/prepared_program.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace clmarch {

/// The median of values (the mean of the middle two for an even count); 0 for none.
double median(std::vector<double> values);

/// Lane-steps that evaluated a marching ray over lane-steps executed, from a render's steps plane
/// (width x height, row-major): a packet of `lanes` pixels (a tile, kernels/lanes.cl) runs as many
/// iterations as its slowest ray; lanes outside the image count as idle. 1 when nothing marched.
double lane_use(const std::vector<float>& steps, int width, int height, int lanes);

/// Recorded points beyond which the ceiling keeps the points of every k-th pixel only (12 bytes
/// each: 16 M points are 192 MB).
inline constexpr std::uint64_t kCeilingMaxSamples = std::uint64_t{1} << 24;
/// Evaluations of each recorded point per run, so that reading it does not limit the rate.
inline constexpr int kCeilingRepeats = 16;

/// The ceiling of the march's distance-evaluation rate: the scene's field evaluated at exactly the
/// points the march of its camera rays evaluates, densely, LANES points per work-item, with no
/// march bookkeeping, no idle lanes and no early exit. The points are recorded once by the march
/// kernel built with RECORD_SAMPLES (same packets, settings and frame as the depth-only render).
/// Built once, run often.
class CeilingKernel {
 public:
  CeilingKernel(const Scene& scene, const OpenClOptions& options, int repeats = kCeilingRepeats,
                std::uint64_t max_samples = kCeilingMaxSamples);
  /// Runs the replay once; returns its milliseconds from the profiling event.
  double run_ms();
  /// Evaluations of one run: samples() * repeats.
  std::uint64_t points() const { return samples_ * static_cast<std::uint64_t>(repeats_); }
  /// Points recorded (all the march's, or those of every pixel_stride()-th pixel).
  std::uint64_t samples() const { return samples_; }
  /// The march's steps over the whole image, as the recording march counted them.
  std::uint64_t marched_steps() const { return marched_steps_; }
  /// 1, or k when only every k-th pixel's points were kept.
  std::uint64_t pixel_stride() const { return pixel_stride_; }
  /// The recorded points, in the frame map() is written in: pixel by pixel in row-major order,
  /// each pixel's in the order the march evaluated them.
  std::vector<glm::vec3> read_samples();
  /// Evaluations the kernel counted in the last run (equal to points()).
  std::uint64_t counted_evaluations() const { return counted_; }
  int lanes() const { return prepared_.lanes; }
  const DeviceProgram& program() const { return prepared_.program; }

 private:
  PreparedProgram prepared_;
  int repeats_ = 1;
  std::uint64_t samples_ = 0;
  std::uint64_t marched_steps_ = 0;
  std::uint64_t pixel_stride_ = 1;
  std::size_t global_items_ = 0;
  std::size_t local_items_ = 0;
  std::size_t plane_ = 0;
  cl::Kernel kernel_;
  std::optional<cl::Buffer> values_;
  cl::Buffer samples_buffer_;
  cl::Buffer sums_;
  cl::Buffer evaluations_;
  std::uint64_t counted_ = 0;
};

/// Floats the depth-only program stores per frame of scene: its planes times the pixels.
std::size_t depth_frame_floats(const Scene& scene);

/// The output floor: the device storing as many floats as a march program writes per frame and
/// doing nothing else (fill_planes of kernels/output_floor.cl, 16 floats per work-item, the count
/// rounded up to whole rows of 16). Built once, run often; each run stores a new value.
class OutputFloorKernel {
 public:
  OutputFloorKernel(const OpenClOptions& options, std::size_t floats);
  /// Fills the buffer once; returns its milliseconds from the profiling event.
  double run_ms();
  /// Floats stored per run.
  std::size_t floats() const { return floats_; }
  /// The buffer as the last run left it.
  std::vector<float> read_back();

 private:
  DeviceProgram program_;
  std::size_t floats_ = 0;
  cl::Kernel kernel_;
  cl::Buffer planes_;
  float value_ = 0.0f;
};

}  // namespace clmarch

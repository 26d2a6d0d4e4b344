// The figures of `clmarch bench` for one scene: kernel times, rays/s, steps per pixel, distance
// evaluations per second against the throughput ceiling, and the time ratios of issue 6.
#pragma once

#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace clmarch {

struct BenchSettings {
  /// Timed runs of each kernel; the median is reported.
  int repeat = 5;
  /// Also time one CPU reference render.
  bool reference = true;
};

struct BenchReport {
  std::string device;
  int lanes = 1;
  Precision precision = Precision::Float;
  int width = 0;
  int height = 0;
  int repeat = 0;
  /// Build of the shaded program in the first (untimed) render; small when the driver's cache has it.
  double build_ms = 0.0;
  /// Median kernel times: the full shaded render and the depth/steps-only render.
  double shaded_ms = 0.0;
  double depth_ms = 0.0;
  /// Pixels per second of the shaded kernel.
  double rays_per_s = 0.0;
  /// March steps (distance evaluations of the march) per pixel.
  double steps_per_pixel = 0.0;
  /// Distance evaluations per second of the depth-only kernel, which evaluates nothing but the march.
  double evals_per_s = 0.0;
  /// Lane-steps that evaluated a marching ray, over those executed (packets march until their
  /// slowest ray ends), in the depth-only render.
  double lane_use = 0.0;
  /// The ceiling (CeilingKernel): evaluations per second of the march's own points, replayed
  /// densely at the same packet width.
  double ceiling_evals_per_s = 0.0;
  double ceiling_ms = 0.0;
  /// Evaluations of one ceiling run: the recorded points times kCeilingRepeats.
  std::uint64_t ceiling_points = 0;
  /// Points recorded from the march (those of every ceiling_pixel_stride-th pixel).
  std::uint64_t ceiling_samples = 0;
  std::uint64_t ceiling_pixel_stride = 1;
  /// evals_per_s / ceiling_evals_per_s.
  double ceiling_ratio = 0.0;
  /// depth_ms / shaded_ms.
  double depth_to_shaded = 0.0;
  /// Median time of the output floor (OutputFloorKernel) storing the floats of the depth-only
  /// program's planes, and its share of depth_ms.
  double output_floor_ms = 0.0;
  double output_floor_share = 0.0;
  int output_floor_planes = 0;
  /// Wall time of one CPU reference render, and shaded_ms / reference_ms.
  std::optional<double> reference_ms;
  std::optional<double> opencl_to_reference;

  nlohmann::json to_json() const;
  /// One figure per line, for people.
  std::string to_text() const;
};

/// Measures scene at its render size on the device and packet width options name.
BenchReport run_bench(const Scene& scene, const OpenClOptions& options, const BenchSettings& settings);

}  // namespace clmarch

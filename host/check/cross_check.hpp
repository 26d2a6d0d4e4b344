// Compares an OpenCL render with the CPU reference pixel by pixel, with tolerances derived from the
// scene's settings (docs/accuracy.md).
#pragma once

#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace clmarch {

/// p50 / p99 / max and root mean square of a set of non-negative errors.
struct ErrorSummary {
  double p50 = 0.0;
  double p99 = 0.0;
  double max = 0.0;
  double rms = 0.0;
};

/// One comparison, the figures of `clmarch check`.
struct CheckReport {
  int pixels = 0;
  int both_hit = 0;
  /// Rays that ran out of render.max_steps on each side (the status channel; not a criterion:
  /// where the step counts differ by one a ray may run out on one side only); none for a render
  /// without the status plane.
  std::optional<std::uint64_t> out_of_steps_opencl;
  std::optional<std::uint64_t> out_of_steps_reference;
  /// Pixels where exactly one side hits, next to a hit/miss edge in either image, or elsewhere.
  int mask_mismatch_silhouette = 0;
  int mask_mismatch_interior = 0;
  /// Pixels holding a NaN or an infinity where the contract has a number (has_non_finite_value).
  int non_finite_opencl = 0;
  int non_finite_reference = 0;
  ErrorSummary depth_abs;
  ErrorSummary depth_rel;
  /// Depth error divided by epsilon, the hit threshold.
  ErrorSummary depth_in_epsilons;
  /// Depth error divided by the pixel's own tolerance (epsilon / cos + float rounding).
  ErrorSummary depth_in_tolerances;
  double steps_diff_mean = 0.0;
  double steps_diff_max = 0.0;
  /// The scene evaluates a union from its operand grid, whose field outside the grid is a lower
  /// bound of the union: its rays take more steps than the reference's there by design, so only
  /// steps the kernel took fewer than the reference count (fewer would still be a fault).
  bool steps_one_sided = false;
  /// Degrees, over pixels both hit.
  double normal_angle_p99 = 0.0;
  /// Pixels both hit whose normal tolerance is pi or more (it would pass any normal): more than the
  /// 1 % the p99 leaves out fail the check. normal_rounding_past_pi counts those where rounding
  /// alone takes it there: then the scene is beyond the precision's reach.
  int normal_tolerance_past_pi = 0;
  int normal_rounding_past_pi = 0;
  double color_max_abs = 0.0;
  /// Over the pixels both hit with equal steps.
  double color_p99_abs = 0.0;
  double color_psnr_db = 0.0;
  /// Over the pixels both miss away from edges (the sky, the background, the glow of misses), those
  /// with equal steps where the scene has Crum's glow.
  double miss_color_p99_abs = 0.0;
  /// Pixels whose color the hit and miss criteria compared, and the misses among them.
  int color_compared = 0;
  int misses_compared = 0;
  /// The shading alone, over the pixels the OpenCL render hit: its color and each of its layers
  /// (ao, diffuse, specular) against the reference's of the same depth, normal and steps
  /// (reshade_hits), so that differences of geometry drop out. Compared pixels: 0 when the check
  /// ran without the reshaded render.
  double shading_max_abs = 0.0;
  double shading_p99_abs = 0.0;
  int shading_compared = 0;
  /// The id channel, with the shading (renders with normals write it): pixels both hit whose
  /// primitive numbers differ, next to an id edge (a neighbour of another number, or a miss, in
  /// either render) or elsewhere; ids_compared is 0 when the check ran without the shading.
  int id_mismatch_edge = 0;
  int id_mismatch_interior = 0;
  int ids_compared = 0;

  /// The tolerances in force, and what failed.
  struct Tolerances {
    int mask_mismatch_interior = 0;
    int mask_mismatch_silhouette = 0;
    double depth_in_tolerances_p99 = 1.0;
    double steps_diff_mean = 1.0;
    double normal_angle_p99 = 0.0;
    double color_p99_abs = 0.0;
    double miss_color_p99_abs = 0.0;
    double shading_p99_abs = 0.0;
    int id_mismatch_interior = 0;
    int id_mismatch_edge = 0;
    /// Pixels both hit whose normal tolerance may pass pi (the 1 % the p99 leaves out).
    double normal_past_pi = 0.0;
  } tolerances;
  /// The p99 over pixels of each error divided by its per-pixel tolerance: at most 1 passes.
  struct ToleranceRatios {
    double normal_p99 = 0.0;
    double color_p99 = 0.0;
    double miss_color_p99 = 0.0;
    double shading_p99 = 0.0;
  } ratios;
  std::vector<std::string> failures;

  bool passed() const { return failures.empty(); }
  nlohmann::json to_json() const;
  /// A short human-readable report, one figure per line; each line that decides the check starts
  /// with PASS or FAIL and names its limit.
  std::string to_text() const;
};

/// Compares opencl (rendered from scene) with reference (the same scene on the CPU reference).
CheckReport cross_check(const Scene& scene, const FrameBuffers& opencl, const FrameBuffers& reference);
/// The same, and the shading alone: reshaded is reshade_hits(scene, opencl), the reference's color
/// of the OpenCL render's own hits. `clmarch check` runs this one.
CheckReport cross_check(const Scene& scene, const FrameBuffers& opencl, const FrameBuffers& reference,
                        const FrameBuffers& reshaded);

/// |a - b| per channel, for the difference image of a failing check.
FrameBuffers difference_image(const FrameBuffers& a, const FrameBuffers& b);

}  // namespace clmarch

// `clmarch bench --sweep`: every combination of settings rendered on OpenCL, timed, and compared
// with a high-accuracy CPU reference of its picture (docs/accuracy.md, "Time against error").
#pragma once

#include "bench/sweep_spec.hpp"
#include "check/cross_check.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <string>
#include <vector>

namespace clmarch {

/// One combination, ready to render: the scene with its scene keys applied, the options with its
/// kernel keys applied.
struct SweepCase {
  SweepCombination combination;
  Scene scene;
  /// What the reference draws: the scene as given with only the combination's picture_sets
  /// applied, so that render.* is measured against the march settings' converged picture.
  Scene picture;
  OpenClOptions options;
  /// True when these are the defaults: the scene file's own settings and the default program.
  bool is_defaults = false;
};

struct SweepSettings {
  /// Timed renders of each combination, interleaved round by round; the median is reported.
  int repeat = 5;
  /// The reference's epsilon in units of the scene's size (the distance from the camera to look_at):
  /// far below any swept epsilon (float itself cannot resolve less than ~1e-7 of the size), and
  /// still well above double's rounding.
  double reference_epsilon_scale = 1e-9;
  /// The reference's step budget: large enough that grazing rays end by hitting or leaving.
  int reference_max_steps = 20000;
  /// The reference's rays a pixel (render.samples, adaptive off) when a sweep varies
  /// render.samples or render.adaptive: its colour error (color_psnr_db) then measures the
  /// anti-aliasing against a converged image. 0: the scene's own.
  int reference_samples = 0;
};

/// Rays a pixel of the reference of a sweep that varies render.samples or render.adaptive.
inline constexpr int kAntialiasedReferenceSamples = 256;

/// What one combination measured.
struct SweepRow {
  SweepCombination combination;
  /// SweepCase::is_defaults.
  bool is_defaults = false;
  /// The settings in force (from the scene and the combination).
  RenderSettings render;
  int lanes = 1;
  KernelVariant variant;
  std::string device;
  /// Median shaded kernel time and all the timed runs.
  double kernel_ms = 0.0;
  std::vector<double> kernel_ms_runs;
  double steps_per_pixel = 0.0;
  /// The render against the reference: depth, mask, normal and color figures (the pass/fail
  /// verdict of `clmarch check` does not apply here).
  CheckReport error;
  /// The epsilon of the reference it was compared with (scaled to its camera's distance).
  double reference_epsilon = 0.0;
  /// The reference's rays a pixel.
  int reference_samples = 1;
};

struct SweepResult {
  int reference_max_steps = 0;
  std::vector<SweepRow> rows;
};

/// scene marched as exactly as the CPU reference can: a fixed epsilon of reference_epsilon_scale
/// times the scene's size, plain sphere tracing, a large step budget, central-difference normals.
/// The normal step stays the scene's normal_epsilon: it is part of the look (fractals and sharp
/// edges have no useful gradient at much finer steps), so a render's normal error is measured
/// against the normal the scene asks for. Step-count AO is off (see run_sweep). With
/// settings.reference_samples, that many rays a pixel, everywhere.
Scene high_accuracy_scene(const Scene& scene, const SweepSettings& settings);

/// Renders the reference of each distinct picture once (one for a sweep of render.* and kernel keys
/// alone; kAntialiasedReferenceSamples rays a pixel where render.samples or render.adaptive is
/// swept, unless settings name a count), then every case: one untimed render whose buffers are compared with its
/// picture's reference, then settings.repeat timed rounds over all cases. Step-count ambient occlusion is turned off in
/// every render: it makes the color a function of the step count, which is what a sweep changes, so it would hide the
/// errors being measured.
SweepResult run_sweep(const std::vector<SweepCase>& cases, SweepSettings settings);

}  // namespace clmarch

// Sweep options to sweep cases: every combination is loaded (and so validated) before the first render.
#include "cli/bench_sweep.hpp"

#include "bench/sweep_csv.hpp"
#include "bench/sweep_run.hpp"
#include "cl/devices.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "render/prepared_program.hpp"
#include "scene/scene_bounds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>

namespace clmarch {
namespace {

/// True when the case renders with march settings and a program equal to scene's with options
/// (automatic settings compared by what they chose: coarse_pass=none on a scene whose auto runs
/// none restates it).
bool same_settings(const SweepCase& c, const Scene& scene, const OpenClOptions& options, const DeviceEntry& device) {
  const auto lanes = [&](const OpenClOptions& o) { return o.lanes.value_or(default_lanes(device)); };
  return resolved_render_settings(c.scene) == resolved_render_settings(scene) && lanes(c.options) == lanes(options) &&
         c.options.variant == options.variant;
}

/// True when a case of a one-at-a-time sweep only restates the base's settings (render.epsilon=1e-4
/// on a scene whose epsilon is 1e-4): the base row measures it already.
bool repeats_base(const SweepCase& c, const Scene& base, const OpenClOptions& base_options, const DeviceEntry& device) {
  for (const std::string& set : scene_sets(c.combination)) {
    if (set.rfind("render.", 0) != 0) return false;
  }
  return same_settings(c, base, base_options, device);
}

}  // namespace

int run_bench_sweep(const BenchCommandOptions& options) {
  if (options.csv.empty()) throw InputError("--sweep needs --csv FILE (where the rows go)");
  check_output_folder(options.csv, "--csv");
  if (options.append) check_sweep_csv_appendable(options.csv);
  std::vector<SweepAxis> axes;
  for (const std::string& text : options.sweeps) axes.push_back(parse_sweep_axis(text));
  const std::vector<SweepCombination> combinations =
      options.one_at_a_time ? expand_one_at_a_time(axes) : expand_sweep(axes);

  const Scene base = load_scene_with_options(options.scene);
  const OpenClOptions base_options = opencl_options(options.scene);
  const DeviceEntry device = select_device(base_options.device);
  // The defaults: the scene file's own march settings (at the same size) and the default program.
  SceneOptions file_options = options.scene;
  file_options.sets.clear();
  const Scene defaults = load_scene_with_options(file_options);
  OpenClOptions default_options;
  default_options.device = base_options.device;
  std::vector<SweepCase> cases;
  for (const SweepCombination& combination : combinations) {
    const auto with_sets = [&](const std::vector<std::string>& sets) {
      SceneOptions scene_options = options.scene;
      scene_options.sets.insert(scene_options.sets.end(), sets.begin(), sets.end());
      // The loader applies swept values as --set; the message says which sweep value it was.
      try {
        return load_scene_with_options(scene_options);
      } catch (const InputError& e) {
        throw InputError(fmt::format("--sweep {}: {}", combination_label(combination), e.what()));
      }
    };
    SweepCase c{combination, with_sets(scene_sets(combination)), with_sets(picture_sets(combination)),
                with_kernel_settings(base_options, combination), false};
    // One precision for the program and the check's tolerances: the swept one, else the scene's.
    const bool sweeps_precision =
        std::any_of(combination.begin(), combination.end(), [](const auto& kv) { return kv.first == "precision"; });
    if (sweeps_precision) {
      c.scene.render.precision = c.options.variant.precision;
    } else {
      c.options.variant = scene_variant(c.scene, c.options.variant);
      if (c.options.variant.precision == Precision::Double && c.options.variant.native_math) {
        throw InputError(
            fmt::format("--sweep {}: native_math=on needs float precision, but the scene has render.precision: "
                        "double (OpenCL has no native_* functions for double)",
                        combination_label(combination)));
      }
    }
    if (options.one_at_a_time && !cases.empty() && repeats_base(c, base, base_options, device)) continue;
    c.is_defaults = same_settings(c, defaults, default_options, device);
    cases.push_back(std::move(c));
  }
  for (const SweepCase& c : cases) {
    if (c.options.variant.precision != Precision::Double) continue;
    if (!device.has_fp64())
      throw InputError(fmt::format("--sweep precision=double: {} has no cl_khr_fp64", device.label()));
  }

  SweepSettings settings;
  settings.repeat = options.repeat;
  const SweepResult result = run_sweep(cases, settings);
  write_sweep_csv(options.csv, options.scene.scene_path, result, options.append);
  log_info(fmt::format("wrote {} rows to {}", result.rows.size(), options.csv));
  return kExitOk;
}

}  // namespace clmarch

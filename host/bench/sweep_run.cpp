// The sweep's measurements: the references first (they load every core), then the OpenCL renders,
// timed in interleaved rounds so that a change of the machine's load spreads over all combinations.
#include "bench/sweep_run.hpp"

#include "bench/throughput.hpp"
#include "common/log.hpp"
#include "reference/reference_renderer.hpp"
#include "scene/scene_bounds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <map>

namespace clmarch {
namespace {

/// The scene as the sweep compares it: without step-count occlusion, whose colours follow step
/// counts that the reference's tiny epsilon changes, but with the automatic choices (coarse pass,
/// over-relaxation) made for the scene as it renders, occlusion included.
Scene without_step_ao(Scene scene) {
  scene.render = resolved_render_settings(scene);
  scene.shading.step_ao = 0.0;
  return scene;
}

}  // namespace

Scene high_accuracy_scene(const Scene& scene, const SweepSettings& settings) {
  Scene out = without_step_ao(scene);
  const double size = glm::length(scene.camera.look_at - scene.camera.position);
  RenderSettings& r = out.render;
  r.epsilon = settings.reference_epsilon_scale * size;
  r.max_steps = settings.reference_max_steps;
  r.hit_threshold = HitThreshold::Fixed;
  r.over_relaxation = 1.0;
  r.normal_method = NormalMethod::Central;
  if (settings.reference_samples > 0) {
    r.samples = settings.reference_samples;
    r.adaptive = false;
  }
  return out;
}

namespace {

/// Whether a case varies the anti-aliasing, whose error only an anti-aliased reference shows.
bool sweeps_antialiasing(const std::vector<SweepCase>& cases) {
  return std::any_of(cases.begin(), cases.end(), [](const SweepCase& c) {
    return std::any_of(c.combination.begin(), c.combination.end(), [](const std::pair<std::string, std::string>& set) {
      return set.first == "render.samples" || set.first == "render.adaptive";
    });
  });
}

}  // namespace

SweepResult run_sweep(const std::vector<SweepCase>& cases, SweepSettings settings) {
  if (settings.reference_samples == 0 && sweeps_antialiasing(cases))
    settings.reference_samples = kAntialiasedReferenceSamples;
  SweepResult result;
  result.reference_max_steps = settings.reference_max_steps;
  // Cases that draw the same picture (the same keys outside render.*) share its reference.
  std::map<std::vector<std::string>, std::pair<FrameBuffers, RenderSettings>> references;
  for (const SweepCase& c : cases) {
    const std::vector<std::string> picture = picture_sets(c.combination);
    if (references.contains(picture)) continue;
    const Scene reference_scene = high_accuracy_scene(c.picture, settings);
    log_info(fmt::format("sweep: CPU reference{}, epsilon {:.3g}, max_steps {}, {} rays a pixel",
                         picture.empty() ? "" : fmt::format(" of {}", fmt::join(picture, " ")),
                         reference_scene.render.epsilon, reference_scene.render.max_steps,
                         reference_scene.render.samples));
    references.emplace(picture, std::pair(render_reference(reference_scene), reference_scene.render));
  }

  std::vector<Scene> scenes;
  scenes.reserve(cases.size());
  for (const SweepCase& c : cases) scenes.push_back(without_step_ao(c.scene));
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const double pixels = static_cast<double>(scenes[k].render.width) * scenes[k].render.height;
    log_info(fmt::format("sweep {}/{}: {}", k + 1, cases.size(), combination_label(cases[k].combination)));
    // The first render pays the build and PoCL's work-group compile; its buffers are the ones compared.
    const RenderResult first = render_opencl(scenes[k], cases[k].options);
    SweepRow row;
    row.combination = cases[k].combination;
    row.render = scenes[k].render;
    row.lanes = first.stats.lanes;
    row.variant = cases[k].options.variant;
    row.device = first.stats.device;
    row.steps_per_pixel = static_cast<double>(first.stats.steps) / pixels;
    row.is_defaults = cases[k].is_defaults;
    const auto& [reference, reference_render] = references.at(picture_sets(cases[k].combination));
    row.error = cross_check(scenes[k], first.buffers, reference);
    row.reference_epsilon = reference_render.epsilon;
    row.reference_samples = reference_render.samples;
    result.rows.push_back(std::move(row));
  }
  for (int round = 0; round < settings.repeat; ++round) {
    log_verbose(fmt::format("sweep: timing round {}/{}", round + 1, settings.repeat));
    for (std::size_t k = 0; k < cases.size(); ++k) {
      // A sweep may have up to kMaxSweepCombinations renderers, too many to keep, so each round
      // makes its own. Its first render loads the program from the driver's cache and takes the
      // fresh output buffer's page faults (a fifth of a 320x180 torus's kernel time); the second
      // one, timed, marches alone as clmarch bench's renders do.
      OpenClRenderer renderer(scenes[k], cases[k].options);
      renderer.render();
      result.rows[k].kernel_ms_runs.push_back(renderer.render().stats.kernel_ms);
    }
  }
  for (SweepRow& row : result.rows) row.kernel_ms = median(row.kernel_ms_runs);
  return result;
}

}  // namespace clmarch

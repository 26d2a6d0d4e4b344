// Benchmarks of scenes/torus.yaml at 1280x720: the shaded and the depth-only render, and the
// throughput ceiling of its distance function (eval_ceiling). Times are the kernels' own, from
// OpenCL profiling events (manual time); counters give rays/s and distance evaluations/s.
#include "bench/throughput.hpp"
#include "scene/scene_loader.hpp"

#include <benchmark/benchmark.h>

namespace clmarch {
namespace {

Scene torus_1280x720() {
  Scene scene = load_scene_file(CLMARCH_SOURCE_DIR "/scenes/torus.yaml");
  scene.render.width = 1280;
  scene.render.height = 720;
  return scene;
}

// Each iteration is one render; the program comes from the driver's cache after the first.
void render_benchmark(benchmark::State& state, KernelPurpose purpose) {
  const Scene scene = torus_1280x720();
  OpenClOptions options;
  options.purpose = purpose;
  render_opencl(scene, options);  // build and PoCL's work-group compile, not timed
  double steps = 0.0, pixels = 0.0;
  for (auto _ : state) {
    const RenderResult result = render_opencl(scene, options);
    state.SetIterationTime(result.stats.kernel_ms * 1e-3);
    steps += static_cast<double>(result.stats.steps);
    pixels += static_cast<double>(scene.render.width) * scene.render.height;
  }
  state.counters["rays/s"] = benchmark::Counter(pixels, benchmark::Counter::kIsRate);
  state.counters["evals/s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
}

void BM_TorusShaded(benchmark::State& state) { render_benchmark(state, KernelPurpose::Shaded); }
void BM_TorusDepthOnly(benchmark::State& state) { render_benchmark(state, KernelPurpose::DepthSteps); }

void BM_TorusCeiling(benchmark::State& state) {
  CeilingKernel ceiling(torus_1280x720(), OpenClOptions{}, 16);
  ceiling.run_ms();  // PoCL compiles the work-group function at the first enqueue
  double evaluations = 0.0;
  for (auto _ : state) {
    state.SetIterationTime(ceiling.run_ms() * 1e-3);
    evaluations += static_cast<double>(ceiling.counted_evaluations());
  }
  state.counters["evals/s"] = benchmark::Counter(evaluations, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_TorusShaded)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TorusDepthOnly)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TorusCeiling)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace clmarch

BENCHMARK_MAIN();

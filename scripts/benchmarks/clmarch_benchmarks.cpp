// Benchmarks of the scenes (scenes/torus.yaml, scenes/mandelbulb.yaml) at 1280x720: the
// shaded and the depth-only render, the throughput ceiling of the scene's distance function
// (CeilingKernel: the march's own points replayed densely) and the output floor of its depth-only
// frame (OutputFloorKernel: its planes stored, nothing else). Times are the kernels' own, from
// OpenCL profiling events (manual time); counters give rays/s, distance evaluations/s and bytes/s.
#include "bench/throughput.hpp"
#include "cl/devices.hpp"
#include "scene/scene_loader.hpp"

#include <benchmark/benchmark.h>

#include <string>

namespace clmarch {
namespace {

Scene scene_1280x720(const std::string& name) {
  Scene scene = load_scene_file(CLMARCH_SOURCE_DIR "/scenes/" + name + ".yaml");
  scene.render.width = 1280;
  scene.render.height = 720;
  return scene;
}

// Each iteration is one render of the same program into the same buffer.
void render_benchmark(benchmark::State& state, const std::string& name, KernelPurpose purpose) {
  const Scene scene = scene_1280x720(name);
  OpenClOptions options;
  options.purpose = purpose;
  OpenClRenderer renderer(scene, options);
  renderer.render();  // PoCL's work-group compile and the buffer's first touch, not timed
  double steps = 0.0, pixels = 0.0;
  for (auto _ : state) {
    const RenderResult result = renderer.render();
    state.SetIterationTime(result.stats.kernel_ms * 1e-3);
    steps += static_cast<double>(result.stats.steps);
    pixels += static_cast<double>(scene.render.width) * scene.render.height;
  }
  state.counters["rays/s"] = benchmark::Counter(pixels, benchmark::Counter::kIsRate);
  state.counters["evals/s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
}

void BM_Shaded(benchmark::State& state, const std::string& name) {
  render_benchmark(state, name, KernelPurpose::Shaded);
}
void BM_DepthOnly(benchmark::State& state, const std::string& name) {
  render_benchmark(state, name, KernelPurpose::DepthSteps);
}

void BM_Ceiling(benchmark::State& state, const std::string& name) {
  CeilingKernel ceiling(scene_1280x720(name), OpenClOptions{});
  ceiling.run_ms();  // PoCL compiles the work-group function at the first enqueue
  double evaluations = 0.0;
  for (auto _ : state) {
    state.SetIterationTime(ceiling.run_ms() * 1e-3);
    evaluations += static_cast<double>(ceiling.counted_evaluations());
  }
  state.counters["evals/s"] = benchmark::Counter(evaluations, benchmark::Counter::kIsRate);
}

void BM_OutputFloor(benchmark::State& state, const std::string& name) {
  const Scene scene = scene_1280x720(name);
  OutputFloorKernel output_floor(OpenClOptions{}, depth_frame_floats(scene));
  output_floor.run_ms();  // PoCL compiles the work-group function at the first enqueue
  double bytes = 0.0;
  for (auto _ : state) {
    state.SetIterationTime(output_floor.run_ms() * 1e-3);
    bytes += static_cast<double>(output_floor.floats() * sizeof(float));
  }
  state.counters["bytes/s"] = benchmark::Counter(bytes, benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Shaded, torus, std::string("torus"))->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DepthOnly, torus, std::string("torus"))->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Ceiling, torus, std::string("torus"))->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_OutputFloor, torus, std::string("torus"))->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Shaded, mandelbulb, std::string("mandelbulb"))->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DepthOnly, mandelbulb, std::string("mandelbulb"))->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Ceiling, mandelbulb, std::string("mandelbulb"))->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace clmarch

int main(int argc, char** argv) {
  clmarch::pin_pocl_threads_for_timing();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// `clmarch bench`'s measurements, in the order that keeps each from disturbing the next: OpenCL
// renders, the ceiling kernel, then the CPU reference (which loads every core).
#include "bench/bench_report.hpp"

#include "bench/throughput.hpp"
#include "codegen/kernel_source.hpp"
#include "reference/reference_renderer.hpp"

#include <fmt/format.h>

#include <chrono>

namespace clmarch {

BenchReport run_bench(const Scene& scene, const OpenClOptions& options, const BenchSettings& settings) {
  BenchReport r;
  r.width = scene.render.width;
  r.height = scene.render.height;
  r.repeat = settings.repeat;
  const double pixels = static_cast<double>(r.width) * r.height;

  OpenClOptions shaded = options;
  shaded.purpose = KernelPurpose::Shaded;
  OpenClOptions depth = options;
  depth.purpose = KernelPurpose::DepthSteps;
  CeilingKernel ceiling(scene, options);
  r.output_floor_planes = static_cast<int>(march_outputs(scene, KernelPurpose::DepthSteps, false).planes().size());
  OutputFloorKernel output_floor(options, depth_frame_floats(scene));
  OpenClRenderer shaded_renderer(scene, shaded);
  OpenClRenderer depth_renderer(scene, depth);
  // One untimed round pays PoCL's work-group compiles and the first touch of the buffers; then the
  // four kernels take turns, so that a change in the machine's load touches all of them and not
  // their ratios.
  RenderResult last_shaded = shaded_renderer.render();
  r.build_ms = last_shaded.stats.build_ms;
  RenderResult last_depth = depth_renderer.render();
  ceiling.run_ms();
  output_floor.run_ms();
  std::vector<double> shaded_ms, depth_ms, ceiling_ms, floor_ms;
  for (int i = 0; i < settings.repeat; ++i) {
    last_shaded = shaded_renderer.render();
    shaded_ms.push_back(last_shaded.stats.kernel_ms);
    last_depth = depth_renderer.render();
    depth_ms.push_back(last_depth.stats.kernel_ms);
    ceiling_ms.push_back(ceiling.run_ms());
    floor_ms.push_back(output_floor.run_ms());
  }
  r.shaded_ms = median(shaded_ms);
  r.device = last_shaded.stats.device;
  r.lanes = last_shaded.stats.lanes;
  r.precision = last_shaded.stats.precision;
  r.rays_per_s = pixels / (r.shaded_ms * 1e-3);

  // Only the march (and the coarse cone pass, if any: one evaluation per block and step) runs in the
  // depth-only program, so its steps are all its distance evaluations.
  r.depth_ms = median(depth_ms);
  r.steps_per_pixel = static_cast<double>(last_depth.stats.steps) / pixels;
  r.evals_per_s = static_cast<double>(last_depth.stats.steps + last_depth.stats.coarse_steps) / (r.depth_ms * 1e-3);
  r.lane_use = lane_use(last_depth.buffers.plane(Channel::Steps), r.width, r.height, r.lanes);
  r.depth_to_shaded = r.depth_ms / r.shaded_ms;
  r.output_floor_ms = median(floor_ms);
  r.output_floor_share = r.output_floor_ms / r.depth_ms;

  r.ceiling_ms = median(ceiling_ms);
  r.ceiling_points = ceiling.points();
  r.ceiling_samples = ceiling.samples();
  r.ceiling_pixel_stride = ceiling.pixel_stride();
  // A scene whose rays all skip the march has no points to replay: no ceiling, ratio 0.
  r.ceiling_evals_per_s =
      r.ceiling_ms > 0.0 ? static_cast<double>(ceiling.counted_evaluations()) / (r.ceiling_ms * 1e-3) : 0.0;
  r.ceiling_ratio = r.ceiling_evals_per_s > 0.0 ? r.evals_per_s / r.ceiling_evals_per_s : 0.0;

  if (settings.reference) {
    const auto start = std::chrono::steady_clock::now();
    render_reference(scene);
    r.reference_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    r.opencl_to_reference = r.shaded_ms / *r.reference_ms;
  }
  return r;
}

nlohmann::json BenchReport::to_json() const {
  const auto or_null = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"device", device},
          {"lanes", lanes},
          {"precision", kPrecisionNames[static_cast<int>(precision)]},
          {"width", width},
          {"height", height},
          {"repeat", repeat},
          {"build_ms", build_ms},
          {"kernel_ms", shaded_ms},
          {"depth_kernel_ms", depth_ms},
          {"rays_per_s", rays_per_s},
          {"steps_per_pixel", steps_per_pixel},
          {"evals_per_s", evals_per_s},
          {"lane_use", lane_use},
          {"ceiling_samples", ceiling_samples},
          {"ceiling_pixel_stride", ceiling_pixel_stride},
          {"ceiling_evals_per_s", ceiling_evals_per_s},
          {"ceiling_kernel_ms", ceiling_ms},
          {"ceiling_points", ceiling_points},
          {"ceiling_ratio", ceiling_ratio},
          {"depth_to_shaded_ratio", depth_to_shaded},
          {"output_floor_ms", output_floor_ms},
          {"output_floor_share", output_floor_share},
          {"output_floor_planes", output_floor_planes},
          {"reference_ms", or_null(reference_ms)},
          {"opencl_to_reference_ratio", or_null(opencl_to_reference)}};
}

std::string BenchReport::to_text() const {
  std::string out = fmt::format("{}x{} on {} ({} lanes, {}), median of {} runs\n", width, height, device, lanes,
                                kPrecisionNames[static_cast<int>(precision)], repeat);
  out += fmt::format("  shaded kernel      {:9.2f} ms   {:.3g} rays/s\n", shaded_ms, rays_per_s);
  out += fmt::format("  depth-only kernel  {:9.2f} ms   {:.2f} of the shaded time\n", depth_ms, depth_to_shaded);
  out += fmt::format("  march steps        {:9.2f} per pixel\n", steps_per_pixel);
  out += fmt::format("  lane use           {:9.2f} of the lane-steps executed\n", lane_use);
  out += fmt::format("  distance evals     {:9.3g} /s  {:.2f} of the ceiling\n", evals_per_s, ceiling_ratio);
  out += fmt::format("  ceiling            {:9.3g} /s  ({} evaluations of {} march points{} in {:.2f} ms)\n",
                     ceiling_evals_per_s, ceiling_points, ceiling_samples,
                     ceiling_pixel_stride > 1 ? fmt::format(", every {}th pixel's", ceiling_pixel_stride) : "",
                     ceiling_ms);
  out += fmt::format(
      "  output floor       {:9.2f} ms   {:.2f} of the depth-only time (storing its {} planes, nothing else)\n",
      output_floor_ms, output_floor_share, output_floor_planes);
  if (reference_ms) {
    out += fmt::format("  CPU reference      {:9.1f} ms   OpenCL shaded takes {:.3f} of it\n", *reference_ms,
                       *opencl_to_reference);
  }
  return out;
}

}  // namespace clmarch

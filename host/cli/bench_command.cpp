// `clmarch bench`.
#include "cli/bench_command.hpp"

#include "bench/bench_report.hpp"
#include "cl/devices.hpp"
#include "cli/bench_sweep.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>

#include <charconv>
#include <iostream>

namespace clmarch {

CLI::App* add_bench_command(CLI::App& app, BenchCommandOptions& options) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Measure a scene's kernel times, rays/s, steps and distance evaluations/s against the device's ceiling");
  bench->footer(
      "Kernel times are medians of --repeat runs from OpenCL profiling events. The ceiling is the scene's\n"
      "distance function evaluated without divergence; the output floor, a kernel that only stores as many\n"
      "floats as the depth-only frame (docs/performance.md).\n"
      "Examples:\n"
      "  clmarch bench scenes/torus.yaml --size 1280x720\n"
      "  clmarch bench scenes/torus.yaml --set render.over_relaxation=1.2 --repeat 9 --json\n"
      "  clmarch bench scenes/mandelbulb.yaml --no-reference --device 0 --lanes 8\n"
      "  clmarch bench scenes/moving_shapes.yaml --time 1.5\n"
      "  clmarch bench scenes/torus.yaml --size 1280x720 --samples 16   # every anti-aliasing pass timed\n"
      "  clmarch bench scenes/torus.yaml --size 320x180 --sweep render.epsilon=1e-2,1e-3,1e-4 --sweep lanes=1,16 --csv "
      "t.csv\n"
      "  clmarch bench scenes/menger.yaml --one-at-a-time --sweep render.max_steps=64,128 --sweep precision=double "
      "--csv m.csv\n"
      "  clmarch bench scenes/torus.yaml --set render.hit_threshold=pixel_cone --sweep render.cone_factor=0.5,1,2 "
      "--append --csv t.csv");
  add_scene_options(*bench, options.scene);
  bench
      ->add_option("--repeat", options.repeat,
                   "Timed runs of each kernel, after one untimed run (default 5; e.g. --repeat 9)")
      ->check(CLI::Validator(
          [](std::string& value) {
            int repeat = 0;
            const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), repeat);
            const bool ok = error == std::errc() && end == value.data() + value.size() && repeat >= 1 && repeat <= 1000;
            return ok ? std::string() : "must be an integer from 1 to 1000 (got '" + value + "')";
          },
          "1..1000", "REPEAT"));
  bench->add_flag("--json", options.json, "Print the figures as one JSON object on stdout");
  bench->add_flag("--no-reference", options.no_reference,
                  "Skip the CPU reference render (slow for large or fractal scenes)");
  bench
      ->add_option("--sweep", options.sweeps,
                   "Sweep a setting: KEY=V1,V2,... with KEY a scene key path or lanes, precision, fast_math, "
                   "native_math; repeat for the Cartesian product (e.g. --sweep render.epsilon=1e-3,1e-4 "
                   "--sweep precision=float,double)")
      ->take_all();
  bench
      ->add_option("--csv", options.csv,
                   "With --sweep: the CSV file of the results, one row per combination (e.g. --csv torus.csv)")
      ->type_name("FILE");
  bench->add_flag("--one-at-a-time", options.one_at_a_time,
                  "With --sweep: the scene as given, then each swept key alone (not every combination)");
  bench->add_flag("--append", options.append,
                  "With --sweep: add the rows to an existing --csv file with the same header");
  return bench;
}

int run_bench_command(const BenchCommandOptions& options) {
  pin_pocl_threads_for_timing();
  if (!options.sweeps.empty()) return run_bench_sweep(options);
  if (!options.csv.empty() || options.append || options.one_at_a_time) {
    throw InputError("--csv, --append and --one-at-a-time need --sweep");
  }
  const Scene scene = load_scene_with_options(options.scene);
  BenchSettings settings;
  settings.repeat = options.repeat;
  settings.reference = !options.no_reference;
  const BenchReport report = run_bench(scene, opencl_options(options.scene), settings);
  if (options.json) {
    nlohmann::json json = report.to_json();
    json["scene"] = options.scene.scene_path;
    std::cout << json.dump() << std::endl;
  } else {
    std::cout << options.scene.scene_path << ": " << report.to_text();
  }
  return kExitOk;
}

}  // namespace clmarch

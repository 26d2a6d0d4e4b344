// `clmarch bench`: the speed of one scene on OpenCL against the device's throughput ceiling and
// the CPU reference (host/bench/), or with --sweep, time against error over combinations of settings.
#pragma once

#include "cli/scene_options.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace clmarch {

struct BenchCommandOptions {
  SceneOptions scene;
  int repeat = 5;
  bool json = false;
  bool no_reference = false;
  /// --sweep KEY=V1,V2,...: time against error over every combination (cli/bench_sweep).
  std::vector<std::string> sweeps;
  std::string csv;
  bool append = false;
  /// Each axis alone around the scene's settings instead of the Cartesian product.
  bool one_at_a_time = false;
};

CLI::App* add_bench_command(CLI::App& app, BenchCommandOptions& options);
int run_bench_command(const BenchCommandOptions& options);

}  // namespace clmarch

// `clmarch bench`: the speed of one scene on OpenCL against the device's throughput ceiling and
// the CPU reference (host/bench/).
#pragma once

#include "cli/scene_options.hpp"

#include <CLI/CLI.hpp>

namespace clmarch {

struct BenchCommandOptions {
  SceneOptions scene;
  int repeat = 5;
  bool json = false;
  bool no_reference = false;
};

CLI::App* add_bench_command(CLI::App& app, BenchCommandOptions& options);
int run_bench_command(const BenchCommandOptions& options);

}  // namespace clmarch

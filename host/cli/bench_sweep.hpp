// `clmarch bench --sweep`: loads every combination of the swept settings (scene keys through the
// --set mechanism), runs the sweep (host/bench/sweep_run) and writes its CSV.
#pragma once

#include "cli/bench_command.hpp"

namespace clmarch {

/// Runs the sweep that options describe; throws InputError for bad --sweep/--csv values before
/// anything is rendered.
int run_bench_sweep(const BenchCommandOptions& options);

}  // namespace clmarch

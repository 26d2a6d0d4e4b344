#!/usr/bin/env bash
# Installs, builds and runs every test (the README's second command; .ci/run calls it):
#   1. the format check (scripts/format.sh --check),
#   2. the suite on the Release build (build/),
#   3. the host-code suites below under AddressSanitizer and UndefinedBehaviorSanitizer
#      (build-sanitize/, clang), whose build also holds the scene fuzzer,
#   4. the scene fuzzer for a bounded time (scripts/fuzz.sh; CLMARCH_FUZZ_SECONDS).
# CLMARCH_QUICK=1 runs steps 1 and 2 only. Each step prints its wall time, and a table of them
# closes the run. All builds treat warnings as errors (CLMARCH_WERROR): a warning fails CI, not just
# the log. scripts/test-profile.sh shows where the suite's time goes.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
stages=()
step() {
  local name=$1
  shift
  local start=$SECONDS
  "$@"
  echo "test.sh: $name took $((SECONDS - start)) s" >&2
  stages+=("$name|$((SECONDS - start))")
}
summary() {
  echo "test.sh: | stage | s |" >&2
  for s in "${stages[@]}"; do echo "test.sh: | ${s%%|*} | ${s##*|} |" >&2; done
  echo "test.sh: | total | $SECONDS |" >&2
}

scripts/setup.sh
# One PoCL kernel cache for this run, empty at its start: the suites' processes and both builds'
# suites share the programs compiled once in it, and no run starts from what an earlier one
# compiled, so every run compiles what it tests.
POCL_CACHE_DIR=$(mktemp -d -t clmarch-test-pocl.XXXXXX)
export POCL_CACHE_DIR
trap 'rm -rf "$POCL_CACHE_DIR"' EXIT

step "format check" scripts/format.sh --check
step "build" scripts/build.sh -DCLMARCH_WERROR=ON
step "tests" ctest --test-dir build --output-on-failure -j "$jobs"
if [ "${CLMARCH_QUICK:-0}" = 1 ]; then
  summary
  exit 0
fi

# The sanitizers instrument the host code, not the driver's compiled kernels, so they run the
# suites that drive the host's code paths: loading and its errors, code generation for every kind,
# the reference renderer, the operand grid, every kernel purpose's buffers, anti-aliasing, check,
# bench and sweeps, frames, MPI, images, interrupts, the command line. They were chosen by
# measurement (scripts/coverage.sh --compare; docs/testing.md has the figures): together they run
# SANITIZED_COVERAGE of the host lines the whole suite runs. The suites left out repeat those paths
# over more scenes for the kernels' sake (every kind far away, golden images, stress sweeps).
sanitized_tests=(
  antialias_test.cpp atomic_file_test.cpp bench_test.cpp blend_operators_test.cpp buffers_exr_test.cpp
  catalogue_exact_test.cpp check_test.cpp cli_errors_test.cpp coarse_pass_test.cpp device_errors_test.cpp
  every_kind_field_test.cpp exit_codes_test.cpp expression_test.cpp first_hour_test.cpp fractal_sdf_test.cpp
  frame_sequence_test.cpp fuzz_regressions_test.cpp help_test.cpp host_memory_test.cpp instance_file_test.cpp
  interrupt_test.cpp kernel_variant_test.cpp mpi_render_test.cpp opencl_renderer_test.cpp operand_grid_test.cpp
  output_failure_test.cpp program_key_test.cpp ray_status_test.cpp reference_cancel_test.cpp
  reference_renderer_test.cpp reference_sdf_test.cpp scene_bounds_test.cpp scene_limits_test.cpp
  scene_loader_test.cpp scene_values_test.cpp shading_layers_test.cpp sweep_test.cpp terrain_sdf_test.cpp
  tiling_test.cpp verbosity_test.cpp views_test.cpp
)
# -O1 -g1: a third of the compile time of -O2 -g under the sanitizers, with file:line in reports;
# Debug keeps assertions on. clang, so that the same build holds the libFuzzer target.
sanitize_build() {
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DCMAKE_CXX_COMPILER=clang++ -DCLMARCH_SANITIZE=ON -DCLMARCH_FUZZ=ON -DCLMARCH_WERROR=ON \
    "-DCLMARCH_TEST_FILES=$(IFS=';'; echo "${sanitized_tests[*]}")" >/dev/null
  cmake --build build-sanitize
}
step "sanitizer build" sanitize_build
# Sanitizer options and the leak suppressions for the OpenCL driver are built into the
# executables (tests/sanitize/sanitizer_defaults.cpp).
step "tests under ASan+UBSan" ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
step "fuzzing" env CLMARCH_FUZZ_BUILD_DIR=build-sanitize scripts/fuzz.sh "${CLMARCH_FUZZ_SECONDS:-60}"
summary

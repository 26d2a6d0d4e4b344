#!/usr/bin/env bash
# Installs, builds and runs every test (the README's second command; .ci/run calls it):
#   1. the format check (scripts/format.sh --check),
#   2. the suite on the Release build (build/),
#   3. the host-code suites below under AddressSanitizer and UndefinedBehaviorSanitizer
#      (build-sanitize/, clang), whose build also holds the scene fuzzer,
#   4. the scene fuzzer for a bounded time: 30 s (scripts/fuzz.sh; CLMARCH_FUZZ_SECONDS=60 as before
#      the library layer, the Python module and the mesh tests took that half minute).
# CLMARCH_QUICK=1 runs steps 1 and 2 only, over a PoCL cache kept between its runs. Each step
# prints its wall time, and a table of them closes the run. All builds treat warnings as errors
# (CLMARCH_WERROR): a warning fails CI, not just the log. scripts/test-profile.sh shows where the
# suite's time goes.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
# ccache keys paths relative to the checkout, so that another clone reuses what this one compiled.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
# The precompiled headers (tests/CMakeLists.txt, host/CMakeLists.txt): ccache caches the sources
# compiled with them only with this sloppiness.
export CCACHE_SLOPPINESS=${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}
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
# compiled, so every run compiles what it tests. CLMARCH_QUICK=1, a developer's loop that CI never
# runs, keeps its cache in build/pocl-cache from run to run instead: a run after a small change
# compiles only the programs the change touched.
if [ "${CLMARCH_QUICK:-0}" = 1 ]; then
  POCL_CACHE_DIR=$PWD/build/pocl-cache
  mkdir -p "$POCL_CACHE_DIR"
else
  POCL_CACHE_DIR=$(mktemp -d -t clmarch-test-pocl.XXXXXX)
  trap 'rm -rf "$POCL_CACHE_DIR"' EXIT
fi
export POCL_CACHE_DIR

step "format check" scripts/format.sh --check
step "build" scripts/build.sh -DCLMARCH_WERROR=ON
step "tests" ctest --test-dir build --output-on-failure -j "$jobs"
if [ "${CLMARCH_QUICK:-0}" = 1 ]; then
  summary
  exit 0
fi

# The sanitizers instrument the host code, not the driver's compiled kernels, so they run the test
# suites that drive the host's code paths, chosen by measurement (scripts/coverage.sh --sanitized,
# 2026-11-27; docs/testing.md): the whole suite runs 7,483 lines of host/, and these 42 suites run
# 7,354 of them (98.3 %): loading and every input error, code generation, the reference, every
# kernel purpose, the operand grid, anti-aliasing, check, bench and sweeps, MPI, images, the command
# line; and the library layer's and the mesh's own suites (RenderSession, SceneRequest, SampleField,
# SceneMesh), added with them; and user GLSL's front end, node and interpreter (GlslFrontEnd,
# GlslNode, GlslInterpreter: host code that reads users' text), and FieldCommand.
# Left out: the suites whose lines the chosen ones run too, above all the sweeps that repeat
# host paths over many programs for the kernels' sake (every kind far away and near, golden images,
# random operand-grid trees: 0 lines of their own), and four that cost a minute or more under the
# sanitizers for a dozen lines of their own (Verbosity 12 lines in 135 s, Scenes/CheckScene 28 in
# 109 s, since merged into Scenes/ShippedScene, FrameSequence 12 in 44 s, Interrupt 2 in 57 s).
sanitized_suites=(
  MpiRender OperandGrid SweepCommand Cli/BadInput CheckFeatures SceneLimits Antialias Bench FarCamera FirstHour Cli
  ColorPattern HostMemory ExitCodes OutputFailure InstanceFile CheckCli ConePass SdfClosedForm ShadingLayers RayStatus
  ProgramKey OpenClRenderer KernelVariant CheckThresholds NodeBoxes DeviceErrors DevicePrograms ReferenceSdf
  ForwardNormals DebugViews SceneLoader DeviceMemory FrameRange StagedFiles RenderReference FractalKeys SdfCode
  FuzzRegressions Expression KernelSource SweepSpec RenderSession SceneRequest SampleField SceneMesh GlslFrontEnd
  GlslNode GlslInterpreter FieldCommand
)
# The test sources that declare those suites: the sanitizer build compiles only them.
sanitized_test_files() {
  local suite name
  for suite in "${sanitized_suites[@]}"; do
    name=${suite##*/}
    grep -lE "\b(TEST|TEST_F|TEST_P)\(\s*${name}\s*,|INSTANTIATE_TEST_SUITE_P\(\s*\w+\s*,\s*${name}\b" tests/*.cpp ||
      { echo "test.sh: no test source declares the suite $suite" >&2; return 1; }
  done | xargs -n1 basename | sort -u | paste -sd ';'
}
# -O1 -g1: a third of the compile time of -O2 -g under the sanitizers, with file:line in reports;
# Debug keeps assertions on. clang, so that the same build holds the libFuzzer target.
sanitize_build() {
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DCMAKE_CXX_COMPILER=clang++ -DCLMARCH_SANITIZE=ON -DCLMARCH_FUZZ=ON -DCLMARCH_WERROR=ON -DCLMARCH_PYTHON=OFF \
    "-DCLMARCH_TEST_FILES=$(sanitized_test_files)" >/dev/null
  cmake --build build-sanitize
}
step "sanitizer build" sanitize_build
# Sanitizer options and the leak suppressions for the OpenCL driver are built into the
# executables (tests/sanitize/sanitizer_defaults.cpp).
step "tests under ASan+UBSan" ctest --test-dir build-sanitize --output-on-failure -j "$jobs" \
  -R "^($(IFS='|'; echo "${sanitized_suites[*]}"))(#[0-9]+)?\$"
step "fuzzing" env CLMARCH_FUZZ_BUILD_DIR=build-sanitize scripts/fuzz.sh "${CLMARCH_FUZZ_SECONDS:-30}"
summary

#!/usr/bin/env bash
# Fuzzes the scene loader and the code generator with libFuzzer for a bounded time.
# Usage: scripts/fuzz.sh [SECONDS]   (default 60; scripts/test.sh runs it in CI)
# Builds build-fuzz/ with clang, ASan and UBSan, warnings as errors (CLMARCH_WERROR). New
# interesting inputs collect in build-fuzz/corpus; an input that crashes, hangs (> 10 s) or trips
# a sanitizer is written to build-fuzz/artifacts/ and the script fails: fix the bug and add the
# input to tests/fuzz_regressions/ (tests/fuzz_regressions_test.cpp then loads it in every test
# run). CLMARCH_FUZZ_BUILD_DIR names a build already configured with CLMARCH_FUZZ=ON to use instead
# (scripts/test.sh's sanitizer build, which serves its tests and the fuzzer alike).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build=${CLMARCH_FUZZ_BUILD_DIR:-build-fuzz}
if [ -z "${CLMARCH_FUZZ_BUILD_DIR:-}" ]; then
  cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DCMAKE_CXX_COMPILER=clang++ -DCLMARCH_FUZZ=ON -DCLMARCH_BUILD_TESTS=OFF -DCLMARCH_WERROR=ON -DCLMARCH_PYTHON=OFF \
    >/dev/null
fi
cmake --build "$build" --target clmarch_fuzz_scene
mkdir -p "$build"/corpus "$build"/artifacts
# The dictionary: the node kinds' names and keys from their declarations, then the other words.
{
  CLMARCH_FUZZ_PRINT_KINDS=1 "$build"/clmarch_fuzz_scene
  cat tests/fuzz/scene.dict
} > "$build"/scene.dict
# The first folder receives new inputs; scenes/ and the regression inputs only seed it.
seeds=(scenes)
[ -d tests/fuzz_regressions ] && seeds+=(tests/fuzz_regressions)
"$build"/clmarch_fuzz_scene -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
  -dict="$build"/scene.dict -artifact_prefix="$build"/artifacts/ -print_final_stats=1 \
  "$build"/corpus "${seeds[@]}" 2> "$build"/fuzz.log || {
  tail -n 60 "$build"/fuzz.log >&2
  echo "fuzz.sh: the fuzzer found a bug; its input is in $build/artifacts/" >&2
  exit 1
}
grep -E "^(stat::number_of_executed_units|Done)" "$build"/fuzz.log >&2 || true
# Generated OpenCL C must compile for every scene the loader accepts: build the programs of up to
# CLMARCH_FUZZ_BUILDS (default 10) accepted corpus inputs on the OpenCL device, newest first.
mapfile -t inputs < <(ls -t "$build"/corpus/* 2>/dev/null)
if [ ${#inputs[@]} -gt 0 ]; then
  CLMARCH_FUZZ_BUILDS=${CLMARCH_FUZZ_BUILDS:-10} "$build"/clmarch_fuzz_scene "${inputs[@]}" \
    > "$build"/builds.log 2>&1 || {
    tail -n 60 "$build"/builds.log >&2
    echo "fuzz.sh: an accepted scene failed to build; the input is named above" >&2
    exit 1
  }
  echo "fuzz.sh: $(grep -c 'an accepted scene built' "$build"/builds.log) accepted corpus scenes built on the device" >&2
fi

#!/usr/bin/env bash
# Installs, builds and runs every test (the README's second command; .ci/run calls it):
#   1. the suite on the Release build (build/),
#   2. the same suite under AddressSanitizer and UndefinedBehaviorSanitizer (build-sanitize/),
#   3. the scene fuzzer for a bounded time (scripts/fuzz.sh, build-fuzz/; CLMARCH_FUZZ_SECONDS).
# CLMARCH_QUICK=1 runs step 1 only. Each step prints its wall time. All three builds treat
# warnings as errors (CLMARCH_WERROR): a warning fails CI, not just the log.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
step() {
  local name=$1
  shift
  local start=$SECONDS
  "$@"
  echo "test.sh: $name took $((SECONDS - start)) s" >&2
}

scripts/setup.sh
step "build" scripts/build.sh -DCLMARCH_WERROR=ON
step "tests" ctest --test-dir build --output-on-failure -j "$jobs"
[ "${CLMARCH_QUICK:-0}" = 1 ] && exit 0

# -O1 -g1: a third of the compile time of -O2 -g under the sanitizers, with file:line in reports;
# Debug keeps assertions on.
sanitize_build() {
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
    -DCLMARCH_SANITIZE=ON -DCLMARCH_WERROR=ON >/dev/null
  cmake --build build-sanitize
}
step "sanitizer build" sanitize_build
# Sanitizer options and the leak suppressions for the OpenCL driver are built into the
# executables (tests/sanitize/sanitizer_defaults.cpp).
step "tests under ASan+UBSan" ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
step "fuzzing" scripts/fuzz.sh "${CLMARCH_FUZZ_SECONDS:-60}"

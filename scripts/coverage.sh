#!/usr/bin/env bash
# Line coverage of host/ by the test suite (gcov): builds build-coverage/ (g++,
# --coverage, -O1), runs the suite, each test group's counts in a folder of its own, and prints each
# file's line coverage, the total and the files under 70 % (scripts/coverage-report.py). With
# --sanitized it also tells how much of that the sanitizer stage's suites run and what each of
# their groups adds (how scripts/test.sh's sanitized_suites were chosen).
# Usage: scripts/coverage.sh [--sanitized]    (about a Release suite's time, plus a build)
set -euo pipefail
cd "$(dirname "$0")/.."
report_args=()
case "${1:-}" in
  "") ;;
  --sanitized)
    source <(sed -n '/^sanitized_suites=(/,/^)/p' scripts/test.sh)
    report_args=(--sanitized "${sanitized_suites[*]}" --costs build-coverage/ctest-junit.xml)
    ;;
  *) echo "coverage.sh: unknown option $1 (expected --sanitized)" >&2; exit 2 ;;
esac
scripts/setup.sh
cmake -S . -B build-coverage -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
  -DCLMARCH_COVERAGE=ON -DCLMARCH_PYTHON=OFF -DCLMARCH_UNITY=OFF >/dev/null
# Counts of an earlier build would clash with the new objects' (the test listing after the build
# writes some): start without any.
find build-coverage -name '*.gcda' -delete 2>/dev/null || true
cmake --build build-coverage
rm -rf build-coverage/coverage-groups
# A PoCL cache of the run's own unless the caller shares one (a warm one saves the compiles).
if [ -z "${POCL_CACHE_DIR:-}" ]; then
  POCL_CACHE_DIR=$(mktemp -d -t clmarch-coverage-pocl.XXXXXX)
  export POCL_CACHE_DIR
  trap 'rm -rf "$POCL_CACHE_DIR"' EXIT
fi
ctest --test-dir build-coverage -j "$(nproc)" --output-junit ctest-junit.xml >build-coverage/ctest.log 2>&1 || {
  tail -n 30 build-coverage/ctest.log >&2
  echo "coverage.sh: tests failed (build-coverage/ctest.log); the coverage below is of the run as it went" >&2
}
scripts/coverage-report.py --build build-coverage "${report_args[@]}"

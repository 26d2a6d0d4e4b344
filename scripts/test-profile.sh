#!/usr/bin/env bash
# Where the test command's time goes (issue 46): runs the Release suite (build/) twice over one
# fresh PoCL cache folder, cold (every OpenCL program compiled) and warm (every program loaded from
# the cache), and prints each test group's time in both runs, their difference (compiling), the
# totals and the most expensive groups (scripts/test-profile.py). Given the log of scripts/test.sh
# it also tables that run's stages; arguments after -- go to ctest (e.g. -- -R '^Check' for some
# groups only).
# Usage: scripts/test-profile.sh [TEST_SH_LOG] [-- CTEST_ARGS...]   (after scripts/build.sh; about
#        twice the suite's time)
set -euo pipefail
cd "$(dirname "$0")/.."
log_args=()
if [ $# -ge 1 ] && [ "$1" != -- ]; then
  log_args=(--log "$1")
  shift
fi
[ "${1:-}" = -- ] && shift
ctest_args=("$@")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export POCL_CACHE_DIR="$out/pocl"
run() {
  local start=$SECONDS
  ctest --test-dir build -j "$(nproc)" --output-junit "$out/$1.xml" "${ctest_args[@]}" >"$out/$1.log" 2>&1 || {
    tail -n 40 "$out/$1.log" >&2
    echo "test-profile.sh: the $1 run failed" >&2
  }
  echo $((SECONDS - start))
}
cold_s=$(run cold)
programs=$(find "$POCL_CACHE_DIR" -name program.bc | wc -l)
warm_s=$(run warm)
scripts/test-profile.py "$out/cold.xml" "$out/warm.xml" --programs "$programs" --wall "$cold_s" "$warm_s" "${log_args[@]}"

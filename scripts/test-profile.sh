#!/usr/bin/env bash
# Where the test command's time goes (issue 46): runs the Release suite (build/) twice over one
# fresh PoCL cache folder, cold (every OpenCL program compiled) and warm (every program loaded from
# the cache), and prints each test group's time in both runs, their difference (compiling), the
# totals and the most expensive groups (scripts/test-profile.py). Given the log of scripts/test.sh
# it also tables that run's stages.
# Usage: scripts/test-profile.sh [TEST_SH_LOG]    (after scripts/build.sh; about twice the suite)
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export POCL_CACHE_DIR="$out/pocl"
run() {
  local start=$SECONDS
  ctest --test-dir build -j "$(nproc)" --output-junit "$out/$1.xml" >"$out/$1.log" 2>&1 || {
    tail -n 40 "$out/$1.log" >&2
    echo "test-profile.sh: the $1 run failed" >&2
  }
  echo $((SECONDS - start))
}
cold_s=$(run cold)
programs=$(find "$POCL_CACHE_DIR" -name program.bc | wc -l)
warm_s=$(run warm)
log_args=()
[ $# -ge 1 ] && log_args=(--log "$1")
scripts/test-profile.py "$out/cold.xml" "$out/warm.xml" --programs "$programs" --wall "$cold_s" "$warm_s" "${log_args[@]}"

#!/usr/bin/env bash
# Runs clang-tidy with the checks of .clang-tidy over every C++ source of host/ and fails on any
# finding (the project keeps it at zero: fix the code, or add a NOLINT(check): reason when it is a
# false positive). Configures build-tidy/ for its compile database; builds nothing.
# Usage: scripts/tidy.sh [-j N] [FILE...]   (default: nproc jobs, every git-tracked host/*.cpp)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
if [ "${1:-}" = -j ]; then
  jobs=${2:?tidy.sh: -j needs a number}
  shift 2
fi
clang_tidy=${CLANG_TIDY:-clang-tidy}
if [ $# -gt 0 ]; then
  files=("$@")
else
  mapfile -t files < <(git ls-files -- 'host/*.cpp')
fi
start=$SECONDS
cmake -S . -B build-tidy -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DCLMARCH_UNITY=OFF \
  -DCLMARCH_BUILD_TESTS=OFF >/dev/null
logs=build-tidy/tidy-logs
rm -rf "$logs"
mkdir -p "$logs"
# One log per file, so that parallel runs do not interleave their lines.
# xargs fails when any clang-tidy did (a finding, or a source that did not parse).
status=0
printf '%s\0' "${files[@]}" | xargs -0 -P "$jobs" -I{} sh -c \
  'exec "$1" -p build-tidy --quiet "$2" > "$3/$(echo "$2" | tr / _).log" 2>&1' _ "$clang_tidy" {} "$logs" \
  || status=$?
# A header's finding is reported once per source that includes it: count each place once.
cat "$logs"/*.log > build-tidy/tidy.log
findings=$({ grep -E '^[^ ]+:[0-9]+:[0-9]+: (warning|error): ' build-tidy/tidy.log || true; } | sort -u | wc -l)
seconds=$((SECONDS - start))
if [ "$findings" -gt 0 ] || [ "$status" -ne 0 ]; then
  grep -vE '^[0-9]+ (warning|error)s? (generated|treated as errors)\.$' build-tidy/tidy.log >&2 || true
  echo "tidy.sh: $findings findings in ${#files[@]} files ($seconds s, -j $jobs); full log in build-tidy/tidy.log" >&2
  exit 1
fi
echo "tidy.sh: ${#files[@]} files clean ($seconds s, -j $jobs)" >&2

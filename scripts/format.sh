#!/usr/bin/env bash
# Formats the project's C++ and OpenCL C with .clang-format, or with --check lists the files that
# differ from it and fails (scripts/test.sh runs the check).
# Usage: scripts/format.sh [--check]
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files -- 'host/*.cpp' 'host/*.hpp' 'kernels/*.cl' 'kernels/*.h' \
  'tests/*.cpp' 'tests/*.hpp' 'scripts/*.cpp' 'scripts/*.c' 'python/src/*.cpp' 'python/src/*.hpp')
if [ "${1:-}" = --check ]; then
  unformatted=()
  for f in "${files[@]}"; do
    clang-format --style=file "$f" | cmp -s - "$f" || unformatted+=("$f")
  done
  if [ ${#unformatted[@]} -gt 0 ]; then
    printf 'format.sh: not formatted by .clang-format (run scripts/format.sh): %s\n' "${unformatted[@]}" >&2
    exit 1
  fi
  echo "format.sh: ${#files[@]} files formatted" >&2
else
  clang-format --style=file -i "${files[@]}"
fi

#!/usr/bin/env bash
# Builds the Google Benchmark program (CLMARCH_BENCHMARKS=ON, in build-bench/) and runs it: the
# 1280x720 torus and Mandelbulb, shaded and depth-only, and their distance functions' throughput
# ceilings. Extra
# arguments go to the program (e.g. --benchmark_repetitions=5 --benchmark_format=json).
# The figures of docs/performance.md come from `clmarch bench` (run at the end).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLMARCH_BENCHMARKS=ON -DCLMARCH_BUILD_TESTS=OFF >/dev/null
cmake --build build-bench --target clmarch clmarch_benchmarks
build-bench/clmarch_benchmarks "$@"
build-bench/clmarch bench scenes/torus.yaml --size 1280x720

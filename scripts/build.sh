#!/usr/bin/env bash
# Configures (Release) and builds clmarch and its tests into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys paths relative to the checkout, so that another clone reuses what this one compiled.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build

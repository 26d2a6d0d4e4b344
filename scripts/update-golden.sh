#!/usr/bin/env bash
# Regenerates the golden images in tests/golden/ from the current build, on purpose. Look at
# every image before committing them: the tests trust these files.
set -euo pipefail
cd "$(dirname "$0")/.."
build/clmarch render scenes/torus.yaml --size 96x54 --lanes 1 -o tests/golden/torus.png

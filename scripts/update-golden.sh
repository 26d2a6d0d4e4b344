#!/usr/bin/env bash
# Regenerates the golden images in tests/golden/ (96x54, one per scene in scenes/) from the current
# build, on purpose. Look at every image before committing them: the tests trust these files.
# Usage: scripts/update-golden.sh [NAME ...]   (scene names, e.g. torus menger; default: every scene)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -eq 0 ]; then
  scenes=(scenes/*.yaml)
else
  scenes=()
  for name in "$@"; do
    [ -f "scenes/$name.yaml" ] || { echo "update-golden.sh: no scene scenes/$name.yaml" >&2; exit 2; }
    scenes+=("scenes/$name.yaml")
  done
fi
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  build/clmarch render "$scene" --size 96x54 --lanes 1 --quiet -o "tests/golden/$name.png"
  echo "update-golden.sh: wrote tests/golden/$name.png; look at it before committing" >&2
done

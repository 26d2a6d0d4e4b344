#!/usr/bin/env bash
# Regenerates the golden images in tests/golden/ (96x54, one per scene in scenes/) from the current
# build, on purpose. Look at every image before committing them: the tests trust these files.
set -euo pipefail
cd "$(dirname "$0")/.."
for scene in scenes/*.yaml; do
  name=$(basename "$scene" .yaml)
  build/clmarch render "$scene" --size 96x54 --lanes 1 --quiet -o "tests/golden/$name.png"
done
echo "update-golden.sh: wrote tests/golden/*.png; look at them before committing" >&2

#!/usr/bin/env bash
# The time-vs-error sweeps of docs/accuracy.md: for each scene, every setting varied alone around
# the scene's own settings, then the pixel-cone factor, at 320x180 on the default OpenCL device.
# Writes docs/sweeps/SCENE.csv and docs/images/sweep_SCENE.png (needs scripts/setup.sh --plots),
# and docs/sweeps/SCENE_samples.csv: render.samples and render.adaptive against a 256-ray reference.
# Usage: scripts/sweep.sh [SCENE_NAME ...]   (default: torus mandelbulb menger terrain_fbm tiled_spheres)
# SWEEP_SIZE (320x180), SWEEP_REPEAT (9) and CLMARCH (build/clmarch) change what runs.
set -euo pipefail
cd "$(dirname "$0")/.."
clmarch=${CLMARCH:-build/clmarch}
size=${SWEEP_SIZE:-320x180}
repeat=${SWEEP_REPEAT:-9}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(torus mandelbulb menger terrain_fbm tiled_spheres)
mkdir -p docs/sweeps docs/images
for name in "${scenes[@]}"; do
  csv=docs/sweeps/$name.csv
  rm -f "$csv"
  # The coarse cone pass does not combine with the cells tiling (the loader refuses it).
  coarse=(--sweep render.coarse_pass=none,cone)
  if grep -q '^tiling:' "scenes/$name.yaml"; then coarse=(); fi
  "$clmarch" bench "scenes/$name.yaml" --size "$size" --repeat "$repeat" --csv "$csv" --one-at-a-time \
    --sweep render.epsilon=1e-2,1e-3,1e-4,1e-5 \
    --sweep render.max_steps=64,128,256,512 \
    --sweep render.over_relaxation=1,1.2,1.5 \
    --sweep render.bounds=none \
    --sweep render.subtree_bounds=none \
    "${coarse[@]}" \
    --sweep render.normal_method=central,tetrahedral,forward \
    --sweep precision=double \
    --sweep fast_math=on \
    --sweep native_math=on \
    --sweep lanes=1,4,8,16
  "$clmarch" bench "scenes/$name.yaml" --size "$size" --repeat "$repeat" --csv "$csv" --append \
    --set render.hit_threshold=pixel_cone --sweep render.cone_factor=0.5,1,2,4
  /usr/bin/python3 scripts/sweep-plot.py "$csv" -o "docs/images/sweep_$name.png"
  # Anti-aliasing against a reference of 256 rays a pixel (its own file: another reference).
  "$clmarch" bench "scenes/$name.yaml" --size "$size" --repeat "$repeat" --csv "docs/sweeps/${name}_samples.csv" \
    --sweep render.samples=1,4,16,64 --sweep render.adaptive=true,false
done

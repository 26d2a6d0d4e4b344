#!/usr/bin/env bash
# Renders the images of docs/tiling.md: the tiled-spheres scene with the cells and mod methods,
# with an off-centre sphere and with the camera 1e6 from the origin.
set -euo pipefail
cd "$(dirname "$0")/.."
out=docs/images
offcentre=(--set sdf.sphere.center=[0.3,0.5,0.5] --set sdf.sphere.radius=0.2)
far=(--set camera.position=[1000000.5,0.15,0.05] --set camera.look_at=[1000003.2,1.9,4.1])
for method in cells mod; do
  build/clmarch render scenes/tiled_spheres.yaml --size 320x180 --set tiling.method=$method "${offcentre[@]}" -o $out/tiling_${method}_offcentre.png
  build/clmarch render scenes/tiled_spheres.yaml --size 320x180 --set tiling.method=$method "${far[@]}" -o $out/tiling_${method}_far.png
done
build/clmarch render scenes/tiled_spheres.yaml --size 320x180 --set shading.view=steps -o $out/tiling_cells_steps.png

#!/usr/bin/env bash
# The pictures of docs/meshes.md: meshes `clmarch mesh` writes, rendered headless by POV-Ray
# through scripts/mesh-picture.py (installs it with scripts/setup.sh --povray). Writes
# docs/images/mesh_*.png; about a minute on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --povray
[ -x build/clmarch ] || scripts/build.sh >/dev/null
cmake --build build --target clmarch >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mesh() { build/clmarch --quiet mesh "$@"; }
picture() { scripts/mesh-picture.py "$@"; }

# The Mandelbulb at 256 cells (marching cubes, smooth normals), from the scene's camera.
mesh scenes/mandelbulb.yaml -o "$tmp/bulb.ply" --resolution 256
picture "$tmp/bulb.ply" docs/images/mesh_mandelbulb.png --camera=2.2,1.5,2.5 --look-at=0,-0.05,0 --fov 40

# Per-vertex colours: the operators demo (union, intersection, smooth union of a red sphere and a
# blue box) at 192 cells, without its floor (a plane has no bounded surface).
grep -v '^    - plane:' scenes/operators_demo.yaml >"$tmp/operators.yaml"
mesh "$tmp/operators.yaml" -o "$tmp/operators.ply" --resolution 192
picture "$tmp/operators.ply" docs/images/mesh_operators.png --camera=0,2.2,6.5 --look-at=0,0,0 --fov 27 \
  --size 800x360

# The triangles of each cell method: the torus at 20 cells, flat, with its edges.
for cells in cubes tetrahedra; do
  mesh scenes/torus.yaml -o "$tmp/torus_$cells.ply" --resolution 20 --cells "$cells"
  picture "$tmp/torus_$cells.ply" "docs/images/mesh_cells_$cells.png" --camera=-1.2,2.4,2.4 --look-at=0,-0.1,0 \
    --fov 40 --flat --edges --size 480x360
done
# Sharp features: the rotated box of the quality tests at 24 cells, without and with --sharp.
printf 'sdf: {box: {half_size: [0.5, 0.3, 0.4], rotate: [10, 20, 30]}}\n' >"$tmp/box.yaml"
for sharp in plain sharp; do
  flag=()
  [ "$sharp" = plain ] || flag=(--sharp)
  mesh "$tmp/box.yaml" -o "$tmp/box_$sharp.ply" --resolution 24 "${flag[@]}"
  picture "$tmp/box_$sharp.ply" "docs/images/mesh_box_$sharp.png" --camera=1.4,1.3,1.9 --look-at=0,0,0 --fov 36 \
    --flat --edges --size 480x360
done
ls -l docs/images/mesh_*.png

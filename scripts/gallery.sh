#!/usr/bin/env bash
# Renders every scene in scenes/ at 480x270, anti-aliased (16 rays where the image shows an edge),
# into docs/images/gallery/ and writes docs/gallery.md with each scene's description and render time.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p docs/images/gallery
{
  echo "# Gallery"
  echo
  echo "Every scene in \`scenes/\`, rendered by \`scripts/gallery.sh\` with the OpenCL path on PoCL"
  echo "(480×270, anti-aliased: \`--samples 16\` with \`render.adaptive\` on, so 16 rays a pixel where the"
  echo "centre rays show an edge and one elsewhere; kernel time of every pass from \`--stats\`, on a 2-core machine)."
  echo
  echo "| article | scenes |"
  echo "|---|---|"
  echo "| Crum, ray marching | torus, smooth_blend, scaffold, mandelbulb, crum_normals |"
  echo "| Heckel, Painting with Math | sphere_shadows, operators_demo, moving_shapes, menger, terrain_fbm, terrain_derivative, martian_landscape |"
  echo "| Ray Marching in Three.js | two_spheres |"
  echo "| An Introduction to Raymarching, the PBR course | pbr_sphere, lava_lamp |"
  echo "| Ray Marching in Infinitely Tiling Space (zebra-north.com) | tiled_spheres, tiled_boxes |"
  echo "| Inigo Quilez's distance functions (the catalogue) | catalogue, mechanical_part, mandelbox |"
  echo "| A shader author's first scene (issue 29) | checker_floor |"
  echo
  for scene in scenes/*.yaml; do
    name=$(basename "$scene" .yaml)
    description=$(sed -n 's/^description: *//p' "$scene")
    stats=$(build/clmarch render "$scene" --size 480x270 --samples 16 --quiet --stats -o "docs/images/gallery/$name.png")
    kernel_ms=$(printf '%s' "$stats" | sed -n 's/.*"kernel_ms":\([0-9.]*\).*/\1/p')
    echo "## $name"
    echo
    echo "$description. \`scenes/$name.yaml\`, kernel $(printf '%.1f' "$kernel_ms") ms."
    echo
    echo "![$name](images/gallery/$name.png)"
    echo
  done
} > docs/gallery.md
echo "gallery.sh: wrote docs/gallery.md" >&2

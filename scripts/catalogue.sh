#!/usr/bin/env bash
# Renders one small picture of every node kind into docs/images/catalogue/ and writes
# docs/catalogue.md: each kind's picture, the node that drew it, its formula in a line and its
# status. The kinds' entries are below (tests/catalogue_docs_test.cpp checks that every kind of
# host/scene/node_kinds.def has one). Usage: scripts/catalogue.sh [NAME ...] (default: every kind).
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p docs/images/catalogue

# name | camera distance | status | formula | node (YAML). Operators' children: a red sphere and a
# blue box (A and B below), or a grey box for single-child operators.
A='{sphere: {center: [-0.25, 0, 0], radius: 0.65, color: [0.9, 0.3, 0.25]}}'
B='{box: {center: [0.3, 0.1, 0.1], half_size: [0.5, 0.5, 0.5], color: [0.25, 0.45, 0.9]}}'
BOX='{box: {half_size: [0.45, 0.35, 0.4], color: [0.8, 0.8, 0.75]}}'
entries=$(cat <<EOF
sphere|3|exact|length(p − c) − r|sphere: {radius: 0.8}
box|3|exact|length(max(q, 0)) + min(maxc(q), 0), q = abs(p − c) − half_size|box: {half_size: [0.6, 0.5, 0.7]}
round_box|3|exact|the box shrunk by radius, less radius|round_box: {half_size: [0.6, 0.5, 0.7], radius: 0.2}
box_frame|3|exact|the twelve edges of a box as square bars|box_frame: {half_size: [0.6, 0.5, 0.7], thickness: 0.06}
torus|3.2|exact|length((length(q.xz) − R, q.y)) − r|torus: {major_radius: 0.8, minor_radius: 0.25}
plane|5|exact|dot(n, p) + offset|plane: {normal: [0.3, 1, 0.2], offset: 0.5, color: {checker: {size: 0.5, colors: [[0.85, 0.85, 0.8], [0.2, 0.2, 0.25]]}}}
capsule|3|exact|distance to the segment a–b, less radius|capsule: {a: [-0.5, -0.4, 0], b: [0.5, 0.5, 0], radius: 0.3}
cylinder|3|exact|2D box of (length(q.xz) − r, abs(q.y) − h)|cylinder: {radius: 0.5, half_height: 0.7}
infinite_cylinder|4|exact|length(q.xz) − r|infinite_cylinder: {radius: 0.4}
octahedron|3|exact|abs(x) + abs(y) + abs(z) ≤ size, by its faces' regions|octahedron: {size: 0.9}
hex_prism|3|exact|hexagon in xz extruded along y|hex_prism: {radius: 0.6, half_height: 0.6}
capped_cone|3|exact|trapezoid (r, y) turned about y|capped_cone: {half_height: 0.7, bottom_radius: 0.6, top_radius: 0.2}
ellipsoid|3|bound outside (Quilez's k0 (k0 − 1) / k1)|k0 = length(q / radii), k1 = length(q / radii²)|ellipsoid: {radii: [0.9, 0.5, 0.6]}
cone|3|exact|apex at centre, base disc height below; (r, y) triangle turned about y|cone: {center: [0, 0.6, 0], angle: 30, height: 1.2}
rounded_cylinder|3|exact|2D box of (length(q.xz), q.y) with its corners rounded by edge_radius|rounded_cylinder: {radius: 0.6, half_height: 0.6, edge_radius: 0.15}
round_cone|3|exact|the hull of the balls of radius_a at a and radius_b at b|round_cone: {a: [0, -0.5, 0], b: [0, 0.6, 0], radius_a: 0.5, radius_b: 0.2}
capped_cylinder|3|exact|the cylinder of radius about the segment a–b, capped flat|capped_cylinder: {a: [-0.4, -0.5, 0.2], b: [0.4, 0.5, -0.2], radius: 0.35}
frustum|3|exact|the cone from radius_a at a to radius_b at b, capped flat|frustum: {a: [-0.3, -0.5, 0.2], b: [0.3, 0.5, -0.2], radius_a: 0.55, radius_b: 0.2}
capped_torus|3.2|exact|the torus's arc of the given half angle about +z|capped_torus: {angle: 120, major_radius: 0.8, minor_radius: 0.2}
link|3.2|exact|a torus stretched by half_length along y (a chain link)|link: {half_length: 0.4, major_radius: 0.45, minor_radius: 0.12}
cut_sphere|3|exact|the sphere above y = cut_height|cut_sphere: {radius: 0.8, cut_height: -0.3}
cut_hollow_sphere|3|exact|the spherical shell below y = cut_height, thickened|cut_hollow_sphere: {radius: 0.8, cut_height: 0.3, thickness: 0.05}
death_star|3.4|exact|the sphere less a sphere carve_distance along +x|death_star: {radius: 0.8, carve_radius: 0.6, carve_distance: 0.9}
solid_angle|3|exact|the ball's cone of the given half angle about +y|solid_angle: {angle: 40, radius: 0.9}
rhombus|3|exact|a rhombus in xz extruded along y, rounded|rhombus: {half_width: 0.8, half_depth: 0.45, half_height: 0.1, corner_radius: 0.08}
triangular_prism|3|bound|an equilateral triangle in xy extruded along z|triangular_prism: {radius: 0.7, half_length: 0.5}
pyramid|3|exact|square base on y = 0, apex height above; side faces and base|pyramid: {center: [0, -0.4, 0], half_width: 0.6, height: 1}
triangle|3|exact (unsigned, thickened)|distance to the triangle abc, less thickness|triangle: {a: [-0.7, -0.4, 0], b: [0.7, -0.4, 0.2], c: [0, 0.7, -0.2], thickness: 0.03}
quad|3|exact (unsigned, thickened)|distance to the planar quad abcd, less thickness|quad: {a: [-0.6, -0.2, -0.6], b: [0.6, -0.2, -0.6], c: [0.6, 0.3, 0.6], d: [-0.6, 0.3, 0.6], thickness: 0.03}
mandelbulb|3|estimate (bound near the set)|0.5 log(r) r / dr of z → z⁸ + c|mandelbulb: {step_factor: 0.8}
menger|3.6|bound|the cube less iterated crosses|menger: {iterations: 3}
sierpinski|4.4|estimate|folds, z → 2 z − (1, 1, 1); distance to the last tetrahedron|sierpinski: {iterations: 6, step_factor: 0.8}
mandelbox|7.5|estimate|box and sphere folds, z → s z + p; abs(z) / dr|mandelbox: {scale: -1.5, iterations: 10, step_factor: 0.8}
julia|3.4|estimate|z → z² + c in quaternions; 0.5 abs(z) log abs(z) / abs(dz)|julia: {step_factor: 0.8}
terrain|6|estimate (bound with a step_factor)|p.y − (height + amplitude · fbm(frequency · p.xz))|terrain: {height: -0.5, amplitude: 0.8, frequency: 0.8, step_factor: 0.5, color: [0.55, 0.45, 0.3]}
circle|3|exact (2D)|length(q.xy) − r; shown extruded|extrude: {half_length: 0.1, children: [{circle: {radius: 0.7}}]}
rectangle|3|exact (2D)|2D box; shown extruded|extrude: {half_length: 0.1, children: [{rectangle: {half_width: 0.8, half_height: 0.5}}]}
rounded_rectangle|3|exact (2D)|2D box shrunk by radius, less radius; shown extruded|extrude: {half_length: 0.1, children: [{rounded_rectangle: {half_width: 0.8, half_height: 0.5, radius: 0.2}}]}
segment|3|exact (2D)|distance to a–b in xy, less radius; shown extruded|extrude: {half_length: 0.1, children: [{segment: {a: [-0.6, -0.4, 0], b: [0.6, 0.4, 0], radius: 0.15}}]}
regular_polygon|3|exact (2D)|distance to the edge of the point's sector; shown extruded|extrude: {half_length: 0.1, children: [{regular_polygon: {radius: 0.7, sides: 5}}]}
union|3|exact outside|min(a, b)|union: [$A, $B]
intersection|3|bound|max(a, b)|intersection: [$A, $B]
subtraction|3|bound|max(a, −b)|subtraction: [$A, $B]
smooth_union|3|bound|polynomial smooth min, blend radius k|smooth_union: {k: 0.3, children: [$A, $B]}
smooth_intersection|3|bound|polynomial smooth max|smooth_intersection: {k: 0.3, children: [$A, $B]}
smooth_subtraction|3|bound|smooth max(a, −b)|smooth_subtraction: {k: 0.3, children: [$A, $B]}
union_chamfer|3|estimate|min(min(a, b), (a + b − r) √½)|union_chamfer: {radius: 0.3, children: [$A, $B]}
intersection_chamfer|3|estimate|max(max(a, b), (a + b + r) √½)|intersection_chamfer: {radius: 0.3, children: [$A, $B]}
difference_chamfer|3|estimate|intersection_chamfer(a, −b)|difference_chamfer: {radius: 0.2, children: [$B, $A]}
union_round|3|estimate|max(r, min(a, b)) − length(max((r − a, r − b), 0))|union_round: {radius: 0.3, children: [$A, $B]}
intersection_round|3|estimate|min(−r, max(a, b)) + length(max((r + a, r + b), 0))|intersection_round: {radius: 0.3, children: [$A, $B]}
difference_round|3|estimate|intersection_round(a, −b)|difference_round: {radius: 0.2, children: [$B, $A]}
union_stairs|3|bound|a staircase of steps across the blend radius|union_stairs: {radius: 0.4, steps: 3, children: [$A, $B]}
intersection_stairs|3|bound|−union_stairs(−a, −b)|intersection_stairs: {radius: 0.4, steps: 3, children: [$A, $B]}
difference_stairs|3|bound|intersection_stairs(a, −b)|difference_stairs: {radius: 0.3, steps: 3, children: [$B, $A]}
union_columns|3|estimate|round columns across the blend radius|union_columns: {radius: 0.4, steps: 3, children: [$A, $B]}
intersection_columns|3|estimate|−union_columns(−a, −b)|intersection_columns: {radius: 0.4, steps: 3, children: [$A, $B]}
difference_columns|3|estimate|intersection_columns(a, −b)|difference_columns: {radius: 0.3, steps: 3, children: [$B, $A]}
xor|3|bound|max(min(a, b), −max(a, b))|xor: [$A, $B]
pipe|3|estimate|length((a, b)) − r|pipe: {radius: 0.06, children: [$A, $B]}
engrave|3|estimate|max(a, (a + r − abs(b)) √½)|engrave: {radius: 0.1, children: [$B, $A]}
groove|3|bound|max(a, min(a + ra, rb − abs(b)))|groove: {ra: 0.1, rb: 0.05, children: [$B, $A]}
tongue|3|bound|min(a, max(a − ra, abs(b) − rb))|tongue: {ra: 0.1, rb: 0.05, children: [$B, $A]}
repeat|6|bound while the child fits its cell|the child at p − period · round(p / period)|intersection: [{repeat: {period: [1.2, 0, 1.2], children: [{sphere: {radius: 0.4, color: [0.9, 0.6, 0.2]}}]}}, {box: {half_size: [1.9, 0.5, 1.9]}}]
displace|3|bound (divided by its Lipschitz factor)|(d + a sin(f x) sin(f y) sin(f z)) / (1 + a f √3)|displace: {amplitude: 0.08, frequency: 8, children: [{sphere: {radius: 0.8, color: [0.6, 0.8, 0.5]}}]}
elongate|3|exact|the child at p − clamp(p, −h, h)|elongate: {h: [0.4, 0, 0], children: [{sphere: {radius: 0.4, color: [0.7, 0.4, 0.9]}}]}
onion|3|exact|abs(d) − thickness (cut open to show the shell)|subtraction: [{onion: {thickness: 0.06, children: [{sphere: {radius: 0.7, color: [0.95, 0.55, 0.2]}}]}}, {box: {center: [0, 0.7, 0.7], half_size: [0.8, 0.7, 0.7]}}]
round|3|exact outside|d − radius|round: {radius: 0.15, children: [$BOX]}
mirror|3|exact|the child at p with abs on the listed axes|mirror: {axes: [x, z], children: [{sphere: {center: [0.45, 0, 0.45], radius: 0.35, color: [0.9, 0.9, 0.9]}}]}
repeat_polar|3.4|bound while the child fits its sector|p turned into the sector of copy 0|repeat_polar: {count: 7, children: [{cylinder: {center: [0.8, 0, 0], radius: 0.15, half_height: 0.3, color: [0.9, 0.2, 0.5]}}]}
repeat_limited|4|bound while the child fits its cell|p − period · clamp(round(p / period), min, max)|repeat_limited: {period: [0.6, 0, 0], min: [-2, 0, 0], max: [2, 0, 0], children: [{octahedron: {size: 0.25, color: [0.4, 0.5, 0.9]}}]}
revolve|3.2|exact for an exact profile|the child's section at (length(p.xz) − offset, p.y, 0)|revolve: {offset: 0.6, children: [{rounded_rectangle: {half_width: 0.2, half_height: 0.5, radius: 0.08, color: [0.3, 0.7, 0.7]}}]}
extrude|3|exact for an exact profile|2D box of (d(p.x, p.y, 0), abs(p.z) − h)|extrude: {half_length: 0.3, children: [{regular_polygon: {radius: 0.7, sides: 6, color: [0.8, 0.6, 0.3]}}]}
twist|3.4|bound (Lipschitz factor of the turn)|the child turned about y by rate · y, over (a + √(a² + 4)) / 2|twist: {rate: 60, children: [{box: {half_size: [0.5, 0.8, 0.25], color: [0.5, 0.8, 0.4]}}]}
bend|3.4|bound (Lipschitz factor of the turn)|the child turned about z by rate · x, over 1 + a|bend: {rate: 40, children: [{box: {half_size: [1, 0.15, 0.3], color: [0.9, 0.7, 0.3]}}]}
nonuniform_scale|3|bound (times the smallest factor)|min(f) d(p / f)|nonuniform_scale: {factors: [1.6, 0.7, 1], children: [{torus: {major_radius: 0.5, minor_radius: 0.2, color: [0.6, 0.4, 0.8]}}]}
glsl|3|bound with a right lipschitz|your GLSL map(p), divided by lipschitz|glsl: {code: 'float map(vec3 p) { p.xz *= mat2(0.8, 0.6, -0.6, 0.8); vec3 q = abs(p) - vec3(0.5, 0.4, 0.6); return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0) - 0.1 + 0.03 * sin(12.0 * p.y); }', lipschitz: 1.4, color: [0.3, 0.7, 0.5]}
EOF
)

wanted=" $* "
{
  echo "# The catalogue"
  echo
  echo "Every node kind, one picture each, rendered by \`scripts/catalogue.sh\` (240×180, 4 rays a pixel"
  echo "at edges, the OpenCL path on PoCL). The node under each picture drew it; the formula is in one"
  echo "line (the full definition, parameters, defaults and allowed ranges are in"
  echo "[scene-format.md](scene-format.md#sdf-nodes)). Status: **exact** is the signed Euclidean distance,"
  echo "**bound** a 1-Lipschitz lower bound of it, **estimate** neither everywhere (give the node a"
  echo "\`step_factor\`). Operators draw a red sphere *a* and a blue box *b*."
  echo
  echo "| picture | kind | status | formula | node |"
  echo "|---|---|---|---|---|"
  while IFS='|' read -r name distance status formula node; do
    [ -n "$name" ] || continue
    if [ "$wanted" = "  " ] || [[ "$wanted" == *" $name "* ]]; then
      eye=$(awk -v d="$distance" 'BEGIN { printf "[%.3f, %.3f, %.3f]", d * 0.55, d * 0.45, d * 0.7 }')
      scene=$(mktemp --suffix=.yaml)
      cat > "$scene" <<SCENE
camera: {position: $eye, look_at: [0, 0, 0], fov: 40}
render: {width: 240, height: 180, max_steps: 600, max_distance: 60, hit_threshold: pixel_cone}
sdf:
  $node
lights: [{directional: {direction: [1, 2, 1.5], intensity: 0.9}}]
shading: {model: blinn_phong, ambient: 0.25, background: [0.12, 0.13, 0.16], shadows: {mode: soft, k: 16}}
SCENE
      build/clmarch render "$scene" --samples 4 --quiet -o "docs/images/catalogue/$name.png"
      rm -f "$scene"
    fi
    echo "| ![$name](images/catalogue/$name.png) | \`$name\` | $status | \`$formula\` | \`$node\` |"
  done <<< "$entries"
} > docs/catalogue.md
echo "catalogue.sh: wrote docs/catalogue.md" >&2

#!/bin/bash
# zoom-sequence.sh [CLMARCH]
#
# How deep each render.precision goes: the Mandelbulb zoom of scenes/zoom/mandelbulb_deep.yaml
# (the camera on the ray through the centre of scenes/mandelbulb.yaml's view, looking at the
# point it hits, vertical fov 0.564 degrees), with the camera D = 2e-1, 2e-2, ..., 2e-7 from that
# point (a view 0.0175 D wide; epsilon and normal_epsilon 5e-6 D, a fifth of a 640-pixel view's
# pixel spacing). For each D and each precision, one markdown row: the pixel spacing on the
# surface, whether `clmarch check` passes at CHECK_SIZE (default 160x90) and its figures (depth
# p99 / epsilon, normal p99, the failures' first words), and the warm kernel time of `clmarch
# render --stats` at 640x360 (the median of RENDERS, default 3). docs/accuracy.md holds a run.
set -euo pipefail
here=$(dirname "$(readlink -f "$0")")
clmarch=${1:-$here/../build/clmarch}
scene=$here/../scenes/zoom/mandelbulb_deep.yaml
check_size=${CHECK_SIZE:-160x90}
renders=${RENDERS:-3}
[ -x "$clmarch" ] || { echo "$0: $clmarch is not an executable" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "| D (camera to surface) | pixel spacing | precision | check | depth p99 / ε | normal p99 | kernel ms (640×360) |"
echo "|---|---|---|---|---|---|---|"
for exponent in 1 2 3 4 5 6 7; do
  # The point hit and the unit ray of the default view (the reference's depth along it, 1e-10 epsilon).
  sets=$(python3 - "$exponent" <<'EOF'
import math, sys
d_cam = 2.0 * 10.0 ** -int(sys.argv[1])
o = [2.2, 1.5, 2.5]
look = [0.0, -0.05, 0.0]
d = [look[i] - o[i] for i in range(3)]
n = math.sqrt(sum(x * x for x in d))
d = [x / n for x in d]
t = 2.658392191
p = [o[i] + t * d[i] for i in range(3)]
c = [p[i] - d_cam * d[i] for i in range(3)]
eps = 5e-6 * d_cam
fmt = lambda v: "[" + ",".join("%.17g" % x for x in v) + "]"
print("camera.position=%s camera.look_at=%s render.epsilon=%.3g render.normal_epsilon=%.3g render.max_distance=%.3g %.3g"
      % (fmt(c), fmt(p), eps, eps, 50 * d_cam, 0.0175 * d_cam / 640))
EOF
)
  spacing=${sets##* }
  read -r -a set_args <<< "${sets% *}"
  args=()
  for s in "${set_args[@]}"; do args+=(--set "$s"); done
  for precision in float double; do
    report=$("$clmarch" check "$scene" --size "$check_size" --json "${args[@]}" --set render.precision=$precision || true)
    figures=$(python3 -c '
import json, sys
r = json.loads(sys.argv[1])
verdict = "passes" if r["passed"] else "fails: " + "; ".join(f.split(",")[0].split(":")[0] for f in r["failures"])
print("%s | %.3g | %.3g°" % (verdict, r["depth_in_epsilons"]["p99"], r["normal_angle_deg_p99"]))' "$report")
    times=()
    for _ in $(seq "$renders"); do
      times+=("$("$clmarch" render "$scene" -o "$tmp/zoom.png" --stats "${args[@]}" --set render.precision=$precision |
        python3 -c 'import json, sys; print(json.loads(sys.stdin.read())["kernel_ms"])')")
    done
    median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }')
    echo "| 2e-$exponent | $spacing | $precision | $figures | $(printf '%.0f' "$median") |"
  done
done

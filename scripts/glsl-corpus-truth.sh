#!/usr/bin/env bash
# The ground truth of the GLSL corpus (issue 42): each tests/glsl_corpus/NAME.glsl's `map` (its .x
# where it returns a vector) and `albedo` (0, 0, 0 where it has none), evaluated by Mesa's llvmpipe
# as GLSL ES 3.00 at the points of tests/glsl_corpus/points.csv at iTime 0 and 1.7, written beside
# it as NAME.t0.csv and NAME.t1.7.csv: x,y,z,distance,r,g,b, 9 significant digits (a float reads
# back exactly). tests/glsl_corpus_test.cpp holds clmarch's two backends to them.
#
# The outputs are committed; regenerate them after editing or adding a corpus file or a point:
#   scripts/setup.sh --peers                      # once: Mesa's EGL, OSMesa and llvmpipe, libpng
#   scripts/glsl-corpus-truth.sh [NAME.glsl ...]  # default: every corpus file
# Needs gcc, /usr/bin/python3 with numpy, and the peer harness glsl_peer.c in PEERS (../shared/peers
# next to the checkout unless the environment names it). Prints one line per file and time.
#
# How: a probe shader per file, the corpus code followed by a mainImage over 2N x 1 pixels; pixel i
# evaluates map at point i into the harness's float output aux_t, pixel N + i albedo at point i
# into the colour. Each pixel is an invocation of its own, so each entry point starts from fresh
# globals, as clmarch evaluates them.
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=tests/glsl_corpus
python=/usr/bin/python3
work=$(mktemp -d -t clmarch-glsl-truth.XXXXXX)
trap 'rm -rf "$work"' EXIT

peers=${PEERS:-$(pwd)/../shared/peers}
[ -f "$peers/glsl_peer.c" ] || { echo "glsl-corpus-truth.sh: no $peers/glsl_peer.c (set PEERS to the peers folder)" >&2; exit 2; }
peer=$work/glsl_peer
gcc -O2 -o "$peer" "$peers/glsl_peer.c" -lEGL -lOSMesa -lpng -lm

# The probe's points as a GLSL const array, and the mainImage that reads them.
"$python" - "$corpus/points.csv" >"$work/probe.glsl" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
n = len(rows)
# The points are multiples of 2^-8 in [-2.5, 2.5]: their decimals are exact floats.
for r in rows:
    for c in "xyz":
        assert float(r[c]) * 256 == int(float(r[c]) * 256) and abs(float(r[c])) <= 2.5, r
points = ",\n  ".join("vec3(%s, %s, %s)" % tuple(repr(float(r[c])) for c in "xyz") for r in rows)
print(f"""
float aux_t = 0.0, aux_steps = 0.0, aux_hit = 0.0;
const int probe_count = {n};
const vec3 probe_points[{n}] = vec3[{n}](
  {points});
float probe_distance(float d) {{ return d; }}
float probe_distance(vec2 d) {{ return d.x; }}
float probe_distance(vec3 d) {{ return d.x; }}
float probe_distance(vec4 d) {{ return d.x; }}
void mainImage(out vec4 color, in vec2 coord) {{
  color = vec4(0.0);
  int i = int(coord.x);
  if (i < probe_count) {{
    aux_t = probe_distance(map(probe_points[i]));
  }} else {{
    PROBE_COLOR
  }}
}}""")
EOF
count=$(($(wc -l <"$corpus/points.csv") - 1))

files=("$@")
if [ ${#files[@]} -eq 0 ]; then files=("$corpus"/*.glsl); fi
for file in "${files[@]}"; do
  name=$(basename "$file" .glsl)
  color="color = vec4(albedo(probe_points[i - probe_count]), 1.0);"
  grep -qE '^vec3 albedo\(vec3 [a-z]+\)' "$corpus/$name.glsl" || color=""
  { cat "$corpus/$name.glsl"; sed "s|PROBE_COLOR|$color|" "$work/probe.glsl"; } >"$work/$name.frag"
  for time in 0 1.7; do
    "$peer" -s "$work/$name.frag" --api gles -W $((2 * count)) -H 1 -n 1 --time "$time" \
      --aux "$work/$name" >/dev/null
    "$python" - "$corpus/points.csv" "$work/$name" "$corpus/$name.t$time.csv" <<'EOF'
import csv, sys
import numpy as np

def read_pfm(path, channels):
    with open(path, "rb") as f:
        kind, size, scale = f.readline(), f.readline(), f.readline()
        assert kind.strip() == (b"PF" if channels == 3 else b"Pf") and float(scale) < 0, path
        width, height = map(int, size.split())
        return np.frombuffer(f.read(), dtype="<f4").reshape(height * width, channels)

rows = list(csv.DictReader(open(sys.argv[1])))
n = len(rows)
distance = read_pfm(sys.argv[2] + "_depth.pfm", 1)[:n, 0]
color = read_pfm(sys.argv[2] + "_color.pfm", 3)[n:]
if not np.isfinite(distance).all() or not np.isfinite(color).all():
    sys.exit(f"{sys.argv[3]}: llvmpipe gave a value that is not finite")
with open(sys.argv[3], "w") as out:
    out.write("x,y,z,distance,r,g,b\n")
    for r, d, c in zip(rows, distance, color):
        values = [d, *c]
        out.write(",".join([r["x"], r["y"], r["z"]] + ["%.9g" % float(v) for v in values]) + "\n")
print(f"{sys.argv[3]}: {n} points, distance in [{distance.min():.3g}, {distance.max():.3g}]")
EOF
  done
done

#!/usr/bin/env bash
# Measures anti-aliasing (render.samples, render.adaptive; docs/performance.md, "Anti-aliasing"):
#  1. the RMS error of the coverage A and of the color against the exact covered area per pixel, on
#     white solids on black under ambient light alone (a disc, a turned square), 1 sample against
#     16 (adaptive and not);
#  2. kernel time (clmarch bench, medians) of adaptive 16 samples against 1 sample at 1280x720 on
#     the torus, the Menger sponge and the Mandelbulb, with the share of pixels refined.
# Usage: scripts/aa-bench.sh [build/clmarch]   (REPEAT=N rounds per bench, default 5)
set -euo pipefail
cd "$(dirname "$0")/.."
clmarch=${1:-build/clmarch}
repeat=${REPEAT:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "== coverage error against the exact area (128x128, camera at z = 5, fov 45)"
for shape in disc square; do
  case $shape in
    disc) sdf='{sphere: {radius: 1}}' ;;
    square) sdf='{box: {half_size: [0.8, 0.8, 0.8], rotate: [0, 0, 30]}}' ;;
  esac
  for run in "1 true" "16 true" "16 false"; do
    set -- $run
    cat >"$work/s.yaml" <<EOF
camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 45}
render: {width: 128, height: 128, samples: $1, adaptive: $2}
shading: {ambient: 1, background: 0}
sdf: $sdf
EOF
    "$clmarch" --quiet render "$work/s.yaml" -o "$work/c.exr" --buffers "$work/b.exr"
    # One channel a file: OpenImageIO may reorder channels it writes together.
    for channel in A R samples; do
      oiiotool "$work/b.exr" --ch "$channel" -o "$work/one.exr"
      oiiotool --dumpdata "$work/one.exr" >"$work/$shape-$1-$2-$channel.txt"
    done
  done
done
python3 - "$work" <<'EOF'
import math, re, sys
work = sys.argv[1]
n = 128
per_pixel = 2 * math.tan(math.radians(22.5)) / n

def disc(x):
    r = math.tan(math.asin(1 / 5))
    if abs(x) >= r:
        return None
    h = math.sqrt(r * r - x * x)
    return (-h, h)

def square(x, s=0.8, angle=math.radians(30)):
    half = s / (5 - s)
    c, sn = math.cos(angle), math.sin(angle)
    low, high = -1e9, 1e9
    for a, b in ((x * c, sn), (-x * sn, c)):
        if abs(b) < 1e-12:
            if abs(a) > half:
                return None
            continue
        y0, y1 = (-half - a) / b, (half - a) / b
        low, high = max(low, min(y0, y1)), min(high, max(y0, y1))
    return (low, high) if high > low else None

def exact(column, i, j, steps=400):
    top, bottom = (n / 2 - j) * per_pixel, (n / 2 - j - 1) * per_pixel
    area = 0.0
    for k in range(steps):
        interval = column((i + (k + 0.5) / steps - n / 2) * per_pixel)
        if interval:
            area += max(0.0, min(interval[1], top) - max(interval[0], bottom)) / per_pixel
    return area / steps

def read(prefix):
    """A, R, samples per pixel from the three one-channel dumps."""
    values = {}
    for channel in ("A", "R", "samples"):
        for line in open(f"{prefix}-{channel}.txt"):
            m = re.match(r"\s*Pixel \((\d+), (\d+)\):\s*(\S+)", line)
            if m:
                values.setdefault((int(m.group(1)), int(m.group(2))), []).append(float(m.group(3)))
    return values

for shape, column in (("disc", disc), ("square", square)):
    truth = {(i, j): exact(column, i, j) for j in range(n) for i in range(n)}
    edge = [p for p, v in truth.items() if 1e-6 < v < 1 - 1e-6]  # the sum of 400 columns rounds
    results = {}
    for run in ("1-true", "16-true", "16-false"):
        px = read(f"{work}/{shape}-{run}")
        rms_a = math.sqrt(sum((px[p][0] - truth[p]) ** 2 for p in edge) / len(edge))
        rms_c = math.sqrt(sum((px[p][1] - truth[p]) ** 2 for p in edge) / len(edge))
        refined = sum(1 for p in px if px[p][2] > 1) / len(px)
        results[run] = rms_a
        print(f"{shape:6} samples {run:9} RMS error over {len(edge)} edge pixels: A {rms_a:.4f}  color {rms_c:.4f}"
              f"  (refined {100 * refined:.1f} % of pixels)")
    print(f"{shape:6} ratio 16 adaptive / 1: {results['16-true'] / results['1-true']:.3f}"
          f"  16 everywhere / 1: {results['16-false'] / results['1-true']:.3f}  (target <= 0.25)")
EOF

echo "== kernel time, 1280x720, clmarch bench --repeat $repeat (medians, ms)"
for scene in torus menger mandelbulb; do
  for samples in 1 16; do
    "$clmarch" --quiet bench "scenes/$scene.yaml" --size 1280x720 --samples "$samples" --repeat "$repeat" --json \
      --no-reference >"$work/$scene-$samples.json"
  done
  "$clmarch" --quiet render "scenes/$scene.yaml" --size 1280x720 --samples 16 -o "$work/x.png" --buffers "$work/x.exr"
  refined=$(oiiotool "$work/x.exr" --ch samples --printstats | sed -n 's/.*Stats Avg: *\([0-9.e+-]*\).*/\1/p' | head -1)
  python3 - "$work/$scene-1.json" "$work/$scene-16.json" "$scene" "$refined" <<'EOF'
import json, sys
one, sixteen = (json.load(open(p)) for p in sys.argv[1:3])
scene, mean_samples = sys.argv[3], float(sys.argv[4])
refined = (mean_samples - 1) / 15
print(f"{scene:10} 1 sample {one['kernel_ms']:8.2f}  adaptive 16 {sixteen['kernel_ms']:8.2f}"
      f"  ratio {sixteen['kernel_ms'] / one['kernel_ms']:5.2f}  refined {100 * refined:5.1f} % of pixels")
EOF
done

#!/usr/bin/env bash
# The figures docs/performance.md gives per device: `clmarch check` of every shipped scene at its
# render size, the torus and Mandelbulb checked at 1280x720 with 1 and 16 lanes, and `clmarch bench`
# of both at 1280x720 and 3840x2160. Run it on the machine whose driver is to be measured:
#   scripts/device-report.sh [--device N] [--out FOLDER]
# FOLDER (default device-report/) receives every result as JSON; the summary goes to stdout.
# CLMARCH names the executable (default build/clmarch). Exit code 1 if any check fails.
set -euo pipefail
cd "$(dirname "$0")/.."
clmarch=${CLMARCH:-build/clmarch}
device=()
out=device-report
while [ $# -gt 0 ]; do
  case "$1" in
    --device) device=(--device "$2"); shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "device-report.sh: unknown option '$1' (expected --device N or --out FOLDER)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
"$clmarch" devices
failed=0
check() {  # NAME, then clmarch check arguments
  local name=$1; shift
  if "$clmarch" check "$@" "${device[@]}" --json >"$out/check_$name.json"; then
    echo "check $name: passed"
  else
    echo "check $name: FAILED (exit $?, $out/check_$name.json)"; failed=1
  fi
}
for scene in scenes/*.yaml; do check "$(basename "$scene" .yaml)" "$scene"; done
for name in torus mandelbulb; do
  for lanes in 1 16; do check "${name}_1280x720_lanes$lanes" "scenes/$name.yaml" --size 1280x720 --lanes "$lanes"; done
done
for name in torus mandelbulb; do
  for size in 1280x720 3840x2160; do
    "$clmarch" bench "scenes/$name.yaml" --size "$size" --repeat 15 "${device[@]}" --json >"$out/bench_${name}_$size.json"
    echo "bench ${name} $size:" $(grep -oE '"(kernel_ms|depth_kernel_ms|ceiling_ratio|depth_to_shaded_ratio|opencl_to_reference_ratio)":[^,}]*' \
      "$out/bench_${name}_$size.json" | tr -d '"')
  done
done
exit $failed

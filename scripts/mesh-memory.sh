#!/usr/bin/env bash
# Peak memory of `clmarch mesh` against resolution (issue 44): the unit sphere meshed at each N
# (default 128 256 512 1024) into a PLY file, one line each: N, bricks sampled, vertices,
# triangles, the memory predicted before sampling, the peak resident memory (/usr/bin/time's %M,
# the whole process: PoCL and its compiler included), the peak less the smallest run's (what the
# mesh itself took), and wall seconds. The target: under 2 GB at 1024, growing with the surface
# (4x a doubling of N), not the volume (8x).
#   scripts/mesh-memory.sh [N...]        (ARGS: more `clmarch mesh` options, e.g. ARGS='--cells tetrahedra')
set -euo pipefail
cd "$(dirname "$0")/.."
resolutions=("$@")
[ ${#resolutions[@]} -gt 0 ] || resolutions=(128 256 512 1024)
[ -x build/clmarch ] || scripts/build.sh >/dev/null
cmake --build build --target clmarch >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'sdf: {sphere: {radius: 1}}\n' >"$tmp/sphere.yaml"
echo "# $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) CPUs, clmarch $(git rev-parse --short HEAD) ${ARGS:-}"
printf '%-6s %8s %10s %10s %14s %10s %12s %7s\n' N bricks vertices triangles predicted_MiB peak_MiB above_base_MiB wall_s
base=""
for n in "${resolutions[@]}"; do
  # shellcheck disable=SC2086
  /usr/bin/time -f '%e %M' -o "$tmp/time" build/clmarch --quiet mesh "$tmp/sphere.yaml" -o "$tmp/sphere.ply" \
    --resolution "$n" --stats ${ARGS:-} >"$tmp/stats"
  read -r wall peak_kib <"$tmp/time"
  [ -n "$base" ] || base=$peak_kib
  /usr/bin/python3 - "$n" "$wall" "$peak_kib" "$base" "$tmp/stats" <<'EOF'
import json, sys
n, wall, peak, base, path = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
s = json.load(open(path))
print(f"{n:<6} {s['bricks']:>8} {s['vertices']:>10} {s['triangles']:>10} {s['predicted_bytes'] / 2**20:>14.0f} "
      f"{peak / 1024:>10.0f} {(peak - base) / 1024:>12.0f} {wall:>7.2f}")
EOF
done

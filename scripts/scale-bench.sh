#!/usr/bin/env bash
# Scene scale (issue 23): whole-process time of a first render with an empty PoCL cache, warm kernel
# time and peak memory, against the number of primitives, for the scenes of scripts/large-scene.py.
#   scripts/scale-bench.sh [SIZES...]      default sizes: 10 100 1000 10000 100000
# Prints a CSV row per scene: kind,primitives,cold_s,kernel_ms,max_rss_mb. Needs build/clmarch.
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(10 100 1000 10000 100000)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "kind,primitives,cold_s,kernel_ms,max_rss_mb"
for kind in spheres molecule; do
  for n in "${sizes[@]}"; do
    scene="$work/$kind-$n.yaml"
    if [ "$n" -gt 5000 ]; then
      scripts/large-scene.py "$kind" "$n" --instances "$work/$kind-$n.csv" > "$scene"
    else
      scripts/large-scene.py "$kind" "$n" > "$scene"
    fi
    export POCL_CACHE_DIR="$work/pocl-$kind-$n"
    /usr/bin/time -f "%e %M" -o "$work/time" build/clmarch render "$scene" -o "$work/out.png" --quiet
    read -r cold rss < "$work/time"
    # Warm: the program is cached now; kernel_ms of a second run.
    kernel=$(build/clmarch render "$scene" -o "$work/out.png" --quiet --stats | sed -n 's/.*"kernel_ms":\([0-9.]*\).*/\1/p')
    echo "$kind,$n,$cold,$kernel,$((rss / 1024))"
  done
done

#!/usr/bin/env bash
# The preview page against a live server (ctest PreviewPage): starts `clmarch preview` on a free
# port with a small scene, runs page_check.js in Node, stops the server with SIGTERM.
# Usage: run_page_check.sh CLMARCH PAGE.html
set -euo pipefail
clmarch=$1
page=$2
dir=$(mktemp -d)
trap 'kill -TERM "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true; rm -rf "$dir"' EXIT
printf 'camera: {position: [0, 1, 4], look_at: [0, 0, 0]}\nrender: {width: 48, height: 32}\nsdf: {sphere: {radius: 1}}\n' \
  >"$dir/scene.yaml"
"$clmarch" preview "$dir/scene.yaml" --port 0 2>"$dir/err.txt" &
server=$!
for _ in $(seq 100); do
  grep -q "Ctrl-C stops it" "$dir/err.txt" && break
  sleep 0.1
done
port=$(grep -o '127\.0\.0\.1:[0-9]*' "$dir/err.txt" | cut -d: -f2)
[ -n "$port" ] || { cat "$dir/err.txt" >&2; exit 1; }
node "$(dirname "$0")/page_check.js" "http://127.0.0.1:$port" "$page"

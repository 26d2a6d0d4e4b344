#!/usr/bin/env bash
# clmarch against the peer a user would otherwise run (issue 24): the four seed scenes as GLSL
# fragment shaders on Mesa's llvmpipe, timed side by side with this build's `clmarch bench` by
# PEERS/speed_vs_peers.sh (PEERS: ../shared/peers next to the checkout unless the environment
# names it). Installs the peer's libraries (scripts/setup.sh --peers) and builds clmarch first.
# Arguments go to speed_vs_peers.sh ([THRESHOLD], default 5), and so does its environment
# (ROUNDS, SIZE, VERBOSE, ...); exit status is its own: 0 when every ratio reaches THRESHOLD.
# About 5 minutes on 2 cores; docs/performance.md#against-the-peer holds the results.
set -euo pipefail
cd "$(dirname "$0")/.."
peers=${PEERS:-$(pwd)/../shared/peers}
[ -x "$peers/speed_vs_peers.sh" ] || { echo "speed-vs-peers.sh: no $peers/speed_vs_peers.sh (set PEERS to the peers folder)" >&2; exit 2; }
scripts/setup.sh --peers
[ -x build/clmarch ] || scripts/build.sh >/dev/null
cmake --build build --target clmarch >/dev/null
exec "$peers/speed_vs_peers.sh" build/clmarch "$@"

#!/usr/bin/env bash
# real-scene-pairs.sh [--check] [CLMARCH]
#
# Issue 41's real-scene benchmark: each pair of benchmarks/real_scenes/ (a clmarch scene and the
# Shadertoy-style GLSL shader of the same picture, benchmarks/real_scenes/README.md) timed side by
# side in one run, the shader on Mesa's llvmpipe through the peers' harness (glsl_peer).
#
#   CLMARCH  the clmarch executable (default: build/clmarch, brought up to date first)
#   --check  exit 1 when a target is missed: cold <= 2 s, warm ratio >= 5, edit (auto) <= 0.5 s
#
# For each of ROUNDS rounds (default 3) and each pair, in alternating order (odd rounds clmarch
# first, even rounds the shader first), these runs, every one after waiting for an idle machine
# (scripts/idle-machine.sh) and redone up to RETRIES (2) times when other processes used more than
# FOREIGN_MAX (0.10) of the machine meanwhile:
#   cold    clmarch render SCENE -o x.png with an empty PoCL cache (POCL_CACHE_DIR=$(mktemp -d)):
#           the whole process's wall time (/usr/bin/time), from start to the written picture;
#   shader  glsl_peer -s SHADER -n 1 with an empty Mesa shader cache: compile_ms + warmup_ms (the
#   cold   program's compile and link, and the first frame, which pays llvmpipe's JIT) as the
#           harness measures them in its process, and the whole process's wall time (which adds
#           the EGL context and one more frame);
#   warm    clmarch bench SCENE --json --no-reference --repeat REPEAT: kernel_ms, the median of
#           the shaded kernel, against glsl_peer -n FRAMES: median_ms of its frames; the ratio;
#   edit    with a PoCL cache that holds the scene's program (warmed before the first round),
#           clmarch render SCENE --set KEY=VALUE -o x.png, a value no run used before (so that
#           a program with spelled literals is new), the whole process's wall time, once with the
#           scene's render.literals (auto) and once with --set render.literals=buffer (its cache
#           warmed with the buffer program). KEY and its first VALUE come from the scene's
#           '# edit: KEY VALUE' line; each edit takes VALUE - 0.002 n.
# Every figure printed is the median over the rounds; foreign is the largest share of the machine
# other processes used during any of the pair's runs. --check holds the auto edit to the target
# (what a user gets); the buffer column shows what the values buffer alone gives.
# Environment: ROUNDS (3), REPEAT (9), FRAMES (10), RETRIES (2), FOREIGN_MAX (0.10), PAIRS (the
# names to run, default all), VERBOSE (1: a '#' line per run), QUIET_WAIT/QUIET_TOTAL
# (idle-machine.sh), GLSL_PEER (the harness; default $TMPDIR/clmarch-glsl-peer, built from
# PEERS/glsl_peer.c when missing, PEERS defaulting to ../shared/peers), SIZE (WxH, default each
# scene's own, 640x360). Exit status: 0, or 1 with --check and a missed target; 2 on a usage error
# or a failed run. About 5 minutes on 2 cores with today's cold builds.
set -u
cd "$(dirname "$0")/.." || exit 2
usage() { echo "usage: $0 [--check] [CLMARCH]" >&2; exit 2; }
check=0
clmarch=""
for arg in "$@"; do
  case "$arg" in
    --check) check=1 ;;
    -*) usage ;;
    *) [ -z "$clmarch" ] || usage; clmarch=$arg ;;
  esac
done
. scripts/clmarch-binary.sh
clmarch=$(clmarch_binary "$clmarch") || exit 2
folder=benchmarks/real_scenes
peer=${GLSL_PEER:-${TMPDIR:-/tmp}/clmarch-glsl-peer}
if [ ! -x "$peer" ]; then   # the peers' harness, built once; scripts/setup.sh --peers installs its libraries
  peers=${PEERS:-$(pwd)/../shared/peers}
  [ -f "$peers/glsl_peer.c" ] || { echo "$0: no $peers/glsl_peer.c (set PEERS to the peers folder)" >&2; exit 2; }
  build_peer() { gcc -O2 -Wall -o "$peer" "$peers/glsl_peer.c" -lEGL -lOSMesa -lpng 2>"${TMPDIR:-/tmp}/glsl_peer.log"; }
  build_peer || { scripts/setup.sh --peers && build_peer; } ||
    { echo "$0: cannot build the peer harness (${TMPDIR:-/tmp}/glsl_peer.log)" >&2; exit 2; }
fi
ROUNDS=${ROUNDS:-3}
REPEAT=${REPEAT:-9}
FRAMES=${FRAMES:-10}
RETRIES=${RETRIES:-2}
FOREIGN_MAX=${FOREIGN_MAX:-0.10}
VERBOSE=${VERBOSE:-0}
PAIRS=${PAIRS:-$(for s in "$folder"/scenes/*.yaml; do basename "$s" .yaml; done)}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. scripts/idle-machine.sh

declare -A edit_key edit_base size_of
for p in $PAIRS; do
  scene=$folder/scenes/$p.yaml
  if [ ! -f "$scene" ] || [ ! -f "$folder/shaders/$p.frag" ]; then
    echo "$0: no pair $p ($scene and its .frag)" >&2; exit 2
  fi
  read -r "edit_key[$p]" "edit_base[$p]" < <(sed -n 's/^# edit: //p' "$scene")
  [ -n "${edit_base[$p]:-}" ] || { echo "$0: $scene has no '# edit: KEY VALUE' line" >&2; exit 2; }
  w=$(sed -n 's/^  width: //p' "$scene"); h=$(sed -n 's/^  height: //p' "$scene")
  size_of[$p]=${SIZE:-${w:-640}x${h:-360}}
done
edits=0

# timed CMD...: runs CMD under /usr/bin/time, stdout to $tmp/out; sets wall (s); exits 2 on failure
timed() {
  /usr/bin/time -f %e -o "$tmp/wall" "$@" >"$tmp/out" 2>"$tmp/err" ||
    { echo "$0: failed: $* : $(tail -3 "$tmp/err")" >&2; exit 2; }
  wall=$(tail -1 "$tmp/wall")
}
# field NAME: NAME's number from the JSON or key=value line in $tmp/out
field() { grep -o "[\" ]$1\"\?[:=][-0-9.eE+]*" "$tmp/out" | head -1 | sed 's/.*[:=]//'; }

# measure KIND PAIR: one run; appends "value1 value2 foreign" to $tmp/PAIR.KIND
measure() {
  local kind=$1 p=$2 scene=$folder/scenes/$2.yaml shader=$folder/shaders/$2.frag try v1 v2 value
  local W=${size_of[$2]%x*} H=${size_of[$2]#*x}
  for ((try = 0; ; try++)); do
    wait_quiet
    foreign_begin
    case $kind in
      cold)
        timed env POCL_CACHE_DIR="$(mktemp -d -p "$tmp")" "$clmarch" --quiet render "$scene" --size "${size_of[$p]}" \
          -o "$tmp/x.png"
        v1=$wall; v2=0 ;;
      shader_cold)
        timed env MESA_SHADER_CACHE_DIR="$(mktemp -d -p "$tmp")" "$peer" -s "$shader" -W "$W" -H "$H" -n 1
        v1=$(awk -v c="$(field compile_ms)" -v w="$(field warmup_ms)" 'BEGIN { printf "%.3f", (c + w) / 1000 }')
        v2=$wall ;;
      warm)
        timed env POCL_CACHE_DIR="$tmp/$p.bench" "$clmarch" --quiet bench "$scene" --size "${size_of[$p]}" --json \
          --no-reference --repeat "$REPEAT"
        v1=$(field kernel_ms); v2=0 ;;
      shader_warm)
        timed "$peer" -s "$shader" -W "$W" -H "$H" -n "$FRAMES"
        v1=$(field median_ms); v2=0 ;;
      edit_auto | edit_buffer)
        edits=$((edits + 1))
        value=$(awk -v b="${edit_base[$p]}" -v n="$edits" 'BEGIN { printf "%.4f", b - 0.002 * n }')
        if [ "$kind" = edit_auto ]; then
          timed env POCL_CACHE_DIR="$tmp/$p.auto" "$clmarch" --quiet render "$scene" --size "${size_of[$p]}" \
            --set "${edit_key[$p]}=$value" -o "$tmp/x.png"
        else
          timed env POCL_CACHE_DIR="$tmp/$p.buffer" "$clmarch" --quiet render "$scene" --size "${size_of[$p]}" \
            --set render.literals=buffer --set "${edit_key[$p]}=$value" -o "$tmp/x.png"
        fi
        v1=$wall; v2=0 ;;
    esac
    foreign_end
    [ -n "$v1" ] || { echo "$0: no figure from $kind $p: $(head -c 300 "$tmp/out")" >&2; exit 2; }
    if awk -v f="$foreign" -v m="$FOREIGN_MAX" 'BEGIN { exit !(f > m) }' && [ "$try" -lt "$RETRIES" ]; then
      echo "# $kind $p: others used $foreign of the machine; again"
      continue
    fi
    echo "$v1 $v2 $foreign" >>"$tmp/$p.$kind"
    [ "$VERBOSE" = 1 ] && echo "# $kind $p: $v1 $v2 foreign $foreign"
    return 0
  done
}

# the edit runs' caches: the scene's program with its own literals and with buffer literals
for p in $PAIRS; do
  scene=$folder/scenes/$p.yaml
  timed env POCL_CACHE_DIR="$tmp/$p.auto" "$clmarch" --quiet render "$scene" --size "${size_of[$p]}" -o "$tmp/x.png"
  timed env POCL_CACHE_DIR="$tmp/$p.buffer" "$clmarch" --quiet render "$scene" --size "${size_of[$p]}" \
    --set render.literals=buffer -o "$tmp/x.png"
done

wait_quiet
echo "# $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) CPUs, $ROUNDS rounds, clmarch $clmarch" \
     "($("$clmarch" --version 2>/dev/null)), bench --repeat $REPEAT, glsl_peer -n $FRAMES"
for ((r = 1; r <= ROUNDS; r++)); do
  for p in $PAIRS; do
    if ((r % 2)); then
      measure cold "$p"; measure shader_cold "$p"; measure warm "$p"; measure shader_warm "$p"
    else
      measure shader_cold "$p"; measure cold "$p"; measure shader_warm "$p"; measure warm "$p"
    fi
    measure edit_auto "$p"; measure edit_buffer "$p"
  done
done
[ "$waited_total" -gt 0 ] && echo "# waited ${waited_total}s in all for the machine to go idle"

printf '%-8s %8s %17s %9s %11s %6s %11s %13s %7s\n' pair cold_s "shader_cold_s" warm_ms llvmpipe_ms ratio \
  edit_auto_s edit_buffer_s foreign
missed=""
for p in $PAIRS; do
  cold=$(median "$tmp/$p.cold" 1)
  scold=$(median "$tmp/$p.shader_cold" 1); swall=$(median "$tmp/$p.shader_cold" 2)
  warm=$(median "$tmp/$p.warm" 1); gl=$(median "$tmp/$p.shader_warm" 1)
  ratio=$(awk -v g="$gl" -v k="$warm" 'BEGIN { printf "%.2f", g / k }')
  auto=$(median "$tmp/$p.edit_auto" 1); buffer=$(median "$tmp/$p.edit_buffer" 1)
  f=$(cat "$tmp/$p.cold" "$tmp/$p.shader_cold" "$tmp/$p.warm" "$tmp/$p.shader_warm" "$tmp/$p.edit_auto" \
        "$tmp/$p.edit_buffer" >"$tmp/all"; largest "$tmp/all" 3)
  printf '%-8s %8.2f %8.2f (%5.2f) %9.1f %11.1f %6s %11.2f %13.2f %7s\n' "$p" "$cold" "$scold" "$swall" "$warm" "$gl" \
    "$ratio" "$auto" "$buffer" "$f"
  awk -v x="$cold" 'BEGIN { exit !(x > 2) }' && missed+=" $p:cold=${cold}s>2s"
  awk -v x="$ratio" 'BEGIN { exit !(x < 5) }' && missed+=" $p:ratio=${ratio}<5"
  awk -v x="$auto" 'BEGIN { exit !(x > 0.5) }' && missed+=" $p:edit=${auto}s>0.5s"
done
echo "# shader_cold_s: the shader's compile + first frame in the harness (its whole process in brackets)"
if [ -n "$missed" ]; then
  echo "targets missed:$missed"
  [ "$check" = 1 ] && exit 1
else
  echo "targets met: cold <= 2 s, warm >= 5x llvmpipe, edit <= 0.5 s"
fi
exit 0

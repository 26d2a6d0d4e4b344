#!/usr/bin/env bash
# cold-start.sh [CLMARCH]
#
# Time to the first picture from an empty PoCL cache, by phase, for every shipped scene
# (scenes/*.yaml and *.json, the list the tests enumerate) and the real-scene pairs
# (benchmarks/real_scenes/scenes/*.yaml), at each scene's own size. Prints a markdown table.
#
#   CLMARCH  the clmarch executable (default: build/clmarch, brought up to date first)
#
# Per scene, each run after waiting for an idle machine (scripts/idle-machine.sh), each with a new
# empty POCL_CACHE_DIR:
#  1. clmarch --verbose render SCENE -o x.png --stats: the whole process's wall time
#     (/usr/bin/time), build_ms (--stats: the program builds plus the first dispatch's wait), the
#     clBuildProgram time ("build N ms") and the first dispatch's wait ("first dispatch waited N ms":
#     PoCL compiles each kernel's work-group function for its local size at its first enqueue).
#  2. The same with POCL_DEBUG=llvm,timing, whose messages carry nanosecond timestamps and time the
#     kernel compiler (PoCL 3.1 has no other phase report: its build options are checked against
#     the OpenCL list, so clang's -ftime-report cannot be passed through POCL_EXTRA_BUILD_FLAGS, and
#     POCL_DEBUG_LLVM_PASSES needs an LLVM built with assertions). From that log:
#       front end   clBuildProgram from "all build options" to "Using ... as the built-in lib":
#                   preprocessing, clang's parse and IR generation, and clang's -O2 pipeline (on by
#                   default for OpenCL C; PoCL turns off only unrolling and vectorisation there);
#       kernel lib  from there to "Writing program.bc": reading PoCL's 9.7 MB built-in library
#                   (kernel-*.bc) and linking the builtins the program calls;
#       WG func     at the first enqueue of each kernel: "llvm_workgroup_ir_func_gen", PoCL's
#                   work-group function (its kernel-compiler passes and the -O3 pipeline with the
#                   vectoriser, which the log does not split);
#       codegen     "Generating an object file directly" to "written ....so.o": LLVM's x86 back end;
#       link        the rest of "llvm_codegen": linking kernel.so;
#     summed over the kernels a render enqueues (kernels).
#  3. Unless REPLAY=0: clang-15 -cc1 (the LLVM of PoCL 3.1) on the program's source (--dump-kernel)
#     with PoCL's options and headers from that log and -ftime-report, which splits the front end:
#     parse (parse and semantic analysis: the front-end timer less the two below), IR gen (LLVM IR
#     generation) and O2 (clang's "Code Generation Time": the -O2 pipeline and the bitcode
#     writer). A replay in another process, not PoCL's own: its total differs from "front end".
# Environment: ROUNDS (1: each figure is the median of the rounds), REPLAY (1), SCENES (the files,
# default all above), QUIET_WAIT/QUIET_TOTAL (idle-machine.sh), VERBOSE (1: each run's figures).
# Exit status 0, 2 on a usage error or a failed run. About 10 minutes on 2 cores today.
set -u
cd "$(dirname "$0")/.." || exit 2
[ $# -le 1 ] || { echo "usage: $0 [CLMARCH]" >&2; exit 2; }
clmarch=${1:-}
. scripts/clmarch-binary.sh
clmarch=$(clmarch_binary "$clmarch") || exit 2
ROUNDS=${ROUNDS:-1}
REPLAY=${REPLAY:-1}
VERBOSE=${VERBOSE:-0}
SCENES=${SCENES:-$(ls scenes/*.yaml scenes/*.json benchmarks/real_scenes/scenes/*.yaml 2>/dev/null)}
pocl_include=/usr/share/pocl/include
if [ "$REPLAY" = 1 ] && ! { command -v clang-15 >/dev/null && [ -f "$pocl_include/_kernel.h" ]; }; then
  echo "# no clang-15 or no $pocl_include: no replay (REPLAY=0)"; REPLAY=0
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. scripts/idle-machine.sh

# the figures of a POCL_DEBUG=llvm,timing log: front end, kernel lib, WG func, codegen, link (ms)
# and the number of kernels compiled
pocl_phases() {
  sed 's/\x1b\[[0-9;]*m//g' "$1" | awk '
    function stamp(line,   a, b) {   # [YYYY-MM-DD HH:MM:SS.nnnnnnnnn] -> seconds of the day
      if (!match(line, /^\[[0-9-]+ [0-9:.]+\]/)) return -1
      split(substr(line, RSTART + 12, RLENGTH - 13), a, ":")
      return a[1] * 3600 + a[2] * 60 + a[3]
    }
    function ms(line,   a) {   # ">>>  63.574  ms  API: x" -> 63.574
      split(substr(line, index(line, ">>>") + 3), a, " ")
      return a[2] == "s" ? a[1] * 1000 : a[2] == "us" ? a[1] / 1000 : a[2] == "ns" ? a[1] / 1e6 : a[1]
    }
    /^\[/ { now = stamp($0); next }
    /all build options:/ { begin = now }
    /as the built-in lib/ && begin > 0 { fe += now - begin; lib_begin = now; begin = 0 }
    /Writing program.bc/ && lib_begin > 0 { lib += now - lib_begin; lib_begin = 0 }
    /API: llvm_workgroup_ir_func_gen/ { wg_k = ms($0); wg += wg_k }
    /Generating an object file directly/ { cg_begin = now }
    /written .*\.so\.o/ && cg_begin > 0 { cg_k = (now - cg_begin) * 1000; cg += cg_k; cg_begin = 0 }
    /API: llvm_codegen/ { link += ms($0) - wg_k - cg_k; wg_k = cg_k = 0; kernels++ }
    END { printf "%.0f %.0f %.0f %.0f %.0f %d\n", fe * 1000, lib * 1000, wg, cg, link, kernels }'
}

# clang-15 -cc1 -ftime-report on the dumped program with PoCL's options: parse, IR gen, O2 (ms)
replay() {
  local scene=$1 options
  options=$(sed 's/\x1b\[[0-9;]*m//g' "$tmp/pocl.log" | sed -n 's/.*all build options: //p' | head -1)
  # --dump-kernel builds the program too: from the phase run's cache
  POCL_CACHE_DIR=$phase_cache "$clmarch" --quiet render "$scene" --dump-kernel "$tmp/k.cl" >/dev/null 2>"$tmp/err" ||
    { echo "- - -"; return; }
  # shellcheck disable=SC2086  # the options are words
  (cd "$tmp" && clang-15 -cc1 $options -include "$pocl_include/pocl_types.h" -include "$pocl_include/_builtin_renames.h" \
     -include "$pocl_include/opencl-c-base.h" -include "$pocl_include/opencl-c.h" -include "$pocl_include/_kernel.h" \
     -fno-unroll-loops -emit-llvm-bc -ftime-report -o /dev/null k.cl) 2>"$tmp/report" ||
    { echo "- - -"; return; }
  awk '
    function wall(line,   n, i, w) {   # the last number outside parentheses: the wall time (s)
      gsub(/\([^)]*\)/, "", line); n = split(line, f, " ")
      for (i = 1; i <= n; i++) if (f[i] ~ /^[0-9.]+$/) w = f[i]
      return w
    }
    /LLVM IR Generation Time/ { ir = wall($0) }
    /Code Generation Time/ { opt = wall($0) }
    /Clang front-end timer/ { total = wall($0) }
    END { printf "%.0f %.0f %.0f\n", (total - ir - opt) * 1000, ir * 1000, opt * 1000 }' "$tmp/report"
}

# timed CMD...: runs CMD under /usr/bin/time, stdout to $tmp/out, stderr to $tmp/err; sets wall (s)
timed() {
  /usr/bin/time -f %e -o "$tmp/wall" "$@" >"$tmp/out" 2>"$tmp/err" ||
    { echo "$0: failed: $* : $(grep -v '^\[\|INFO' "$tmp/err" | tail -3)" >&2; exit 2; }
  wall=$(tail -1 "$tmp/wall")
}

wait_quiet
echo "# $(date -u +%FT%TZ) load $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) CPUs, $(uname -m)," \
     "clmarch $clmarch ($("$clmarch" --version 2>/dev/null)), $ROUNDS round(s), an empty PoCL cache per run"
for scene in $SCENES; do
  name=${scene#scenes/}; name=${name/benchmarks\/real_scenes\/scenes\//real_scenes\/}; key=${name//\//_}
  for ((r = 1; r <= ROUNDS; r++)); do
    wait_quiet
    foreign_begin
    timed env POCL_CACHE_DIR="$(mktemp -d -p "$tmp")" "$clmarch" --verbose render "$scene" -o "$tmp/x.png" --stats
    foreign_end
    build=$(grep -o '"build_ms":[0-9.]*' "$tmp/out" | cut -d: -f2)
    program=$(grep -o 'clmarch: build [0-9]* ms' "$tmp/err" | awk '{ s += $3 } END { print s + 0 }')
    dispatch=$(grep -o 'first dispatch waited [0-9]* ms' "$tmp/err" | awk '{ s += $4 } END { print s + 0 }')
    wait_quiet
    phase_cache=$(mktemp -d -p "$tmp")
    timed env POCL_CACHE_DIR="$phase_cache" POCL_DEBUG=llvm,timing "$clmarch" render "$scene" -o "$tmp/x.png"
    cp "$tmp/err" "$tmp/pocl.log"
    phases=$(pocl_phases "$tmp/pocl.log")
    if [ "$REPLAY" = 1 ]; then split=$(replay "$scene"); else split="- - -"; fi
    echo "$wall $build $program $dispatch $phases $split $foreign" >>"$tmp/$key.runs"
    [ "$VERBOSE" = 1 ] && echo "# $name: $wall $build $program $dispatch $phases $split $foreign"
  done
done
[ "$waited_total" -gt 0 ] && echo "# waited ${waited_total}s in all for the machine to go idle"

echo
echo "| scene | whole process s | build_ms | clBuildProgram ms | first dispatch ms | front end ms | kernel lib ms" \
     "| WG func ms | codegen ms | link ms | kernels | replay: parse ms | IR gen ms | O2 ms | foreign |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for scene in $SCENES; do
  name=${scene#scenes/}; name=${name/benchmarks\/real_scenes\/scenes\//real_scenes\/}; key=${name//\//_}
  row="| $name"
  for c in 1 2 3 4 5 6 7 8 9 10 11 12 13; do
    if awk -v c="$c" '$c == "-" { exit 1 }' "$tmp/$key.runs"; then
      v=$(median "$tmp/$key.runs" "$c")
      case $c in 1) v=$(printf '%.2f' "$v") ;; *) v=$(printf '%.0f' "$v") ;; esac
    else
      v=-
    fi
    row+=" | $v"
  done
  echo "$row | $(largest "$tmp/$key.runs" 14) |"
done
echo
echo "build_ms = clBuildProgram + first dispatch; front end + kernel lib ~ clBuildProgram; WG func + codegen +" \
     "link ~ first dispatch. foreign: the largest share of the machine other processes used during run 1."

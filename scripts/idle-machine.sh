# shellcheck shell=bash disable=SC2154,SC2034,SC2207  # $tmp is the caller's, foreign is for it; ticks are words
# Sourced by the timing scripts (real-scene-pairs.sh, cold-start.sh): waits for an idle machine
# before a run and measures the share of the machine's CPU that other processes used during it, as
# ../shared/peers/speed_vs_peers.sh does. Needs $tmp (a scratch folder) and reads QUIET_WAIT (300:
# the most seconds to wait before one run), QUIET_TOTAL (900: in all) and QUIET_BUSY (0.10: the
# busy share below which the machine counts as idle over 1 s).

QUIET_WAIT=${QUIET_WAIT:-300}
QUIET_TOTAL=${QUIET_TOTAL:-900}
QUIET_BUSY=${QUIET_BUSY:-0.10}
HZ=$(getconf CLK_TCK 2>/dev/null || echo 100)
waited_total=0

# "total busy" CPU ticks of the whole machine, from /proc/stat
machine_ticks() { awk '/^cpu / { t = 0; for (i = 2; i <= 9; i++) t += $i; print t, t - $5 - $6; exit }' /proc/stat; }

# CPU seconds used by this shell's finished children, into child_s (the `times` builtin must run in
# this shell, not in a $(...) subshell, whose children start from zero)
child_cpu() {
  times >"$tmp/times"
  child_s=$(awk 'NR == 2 { s = 0; for (i = 1; i <= 2; i++) { split($i, a, "m"); s += a[1] * 60 + a[2] } printf "%.3f", s }' "$tmp/times")
}

# Waits until the machine is idle (busy < QUIET_BUSY over 1 s), at most QUIET_WAIT s, and no longer
# once QUIET_TOTAL s were spent waiting in all.
wait_quiet() {
  local waited=0 a b busy
  while [ "$QUIET_WAIT" -gt 0 ] && [ "$waited_total" -lt "$QUIET_TOTAL" ]; do
    a=($(machine_ticks)); sleep 1; b=($(machine_ticks))
    busy=$(awk -v t=$((b[0] - a[0])) -v u=$((b[1] - a[1])) 'BEGIN { printf "%.2f", (t > 0 ? u / t : 0) }')
    awk -v x="$busy" -v m="$QUIET_BUSY" 'BEGIN { exit !(x < m) }' && return 0
    if [ "$waited" -ge "$QUIET_WAIT" ]; then
      echo "# WARNING: machine still busy ($busy) after ${waited}s; measuring anyway"; return 0
    fi
    sleep 4; waited=$((waited + 5)); waited_total=$((waited_total + 5))
  done
}

# Call foreign_begin before a run and foreign_end after it: foreign_end sets foreign, the share of
# the machine's CPU time that other processes used meanwhile (this shell's children excluded).
foreign_begin() { foreign_t0=($(machine_ticks)); child_cpu; foreign_c0=$child_s; }
foreign_end() {
  local t1
  t1=($(machine_ticks)); child_cpu
  foreign=$(awk -v t=$((t1[0] - foreign_t0[0])) -v u=$((t1[1] - foreign_t0[1])) -v c0="$foreign_c0" -v c1="$child_s" \
            -v hz="$HZ" 'BEGIN { f = t > 0 ? (u / hz - (c1 - c0)) / (t / hz) : 0; printf "%.3f", (f < 0 ? 0 : f) }')
}

# median of column $2 of file $1 (3 decimals); largest value of column $2
median() { sort -g -k"$2","$2" "$1" | awk -v c="$2" '{ v[NR] = $c } END {
  if (NR == 0) { printf "-"; exit }
  if (NR % 2) printf "%.3f", v[(NR + 1) / 2]; else printf "%.3f", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
largest() { awk -v c="$2" 'BEGIN { m = 0 } $c > m { m = $c } END { printf "%.2f", m }' "$1"; }

# Sourced by the benchmark scripts: clmarch_binary [PATH] prints the absolute path of the clmarch
# executable to time, PATH when given, else build/clmarch built (or brought up to date) first;
# with a message on stderr and status 2 when there is none. It also checks for /usr/bin/time,
# which every such script times with.
clmarch_binary() {
  local clmarch=${1:-}
  if [ -z "$clmarch" ]; then
    [ -x build/clmarch ] || scripts/build.sh >/dev/null || return 2
    cmake --build build --target clmarch >/dev/null || return 2
    clmarch=build/clmarch
  fi
  [ -x "$clmarch" ] || { echo "$0: $clmarch is not an executable" >&2; return 2; }
  [ -x /usr/bin/time ] || { echo "$0: needs /usr/bin/time (Debian: apt-get install time)" >&2; return 2; }
  readlink -f "$clmarch"
}

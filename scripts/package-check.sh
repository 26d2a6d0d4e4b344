#!/usr/bin/env bash
# Shows that the Debian package installs and renders on a fresh Debian 12: builds it
# (scripts/package.sh), bootstraps a minimal bookworm root with debootstrap, installs the .deb, PoCL
# and man-db there with apt-get, and runs clmarch --version, clmarch devices, a render of an
# installed scene, its bash completion and man clmarch inside it. Prints the package's fields and
# lintian's findings on the way. Needs root, debootstrap and lintian (scripts/setup.sh
# --package-check) and a Debian mirror; downloads about 150 MB. Not part of scripts/test.sh.
# Usage: scripts/package-check.sh [MIRROR]   (default http://deb.debian.org/debian)
set -euo pipefail
cd "$(dirname "$0")/.."
mirror=${1:-http://deb.debian.org/debian}
say() { echo "package-check: [$SECONDS s] $*" >&2; }

if [ "$(id -u)" -ne 0 ]; then
  echo "package-check.sh: run as root (debootstrap, chroot and mount need it)" >&2
  exit 1
fi
if ! command -v debootstrap >/dev/null; then
  echo "package-check.sh: debootstrap is missing: run scripts/setup.sh --package-check" >&2
  exit 1
fi

say "building the package"
deb=$(scripts/package.sh | tail -n 1)
say "built $deb ($(du -k "$deb" | cut -f1) KiB)"
dpkg-deb --info "$deb" >&2
dpkg-deb --contents "$deb" >&2
if command -v lintian >/dev/null; then
  say "lintian (its findings are reported, not fatal):"
  lintian --info "$deb" >&2 || true
fi

root=$(mktemp -d -t clmarch-bookworm.XXXXXX)
cleanup() {
  local mounted=0 point
  for point in dev sys proc; do
    if mountpoint -q "$root/$point"; then umount "$root/$point" || umount -l "$root/$point" || mounted=1; fi
  done
  # Never delete through a mount that is still there.
  if [ $mounted -eq 0 ]; then rm -rf --one-file-system "$root"; else echo "package-check: left $root" >&2; fi
}
trap cleanup EXIT

say "debootstrap --variant=minbase bookworm into $root"
debootstrap --variant=minbase bookworm "$root" "$mirror" >"$root.debootstrap.log" 2>&1 ||
  { tail -n 20 "$root.debootstrap.log" >&2; exit 1; }
rm -f "$root.debootstrap.log"
mount -t proc proc "$root/proc"
mount -t sysfs sysfs "$root/sys"
mount --bind /dev "$root/dev"
cp "$deb" "$root/tmp/"
# A clean environment: nothing of this machine's (PATH, POCL_*, locale) reaches the root.
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root TERM=dumb \
  DEBIAN_FRONTEND=noninteractive /bin/bash -euo pipefail -c "$1"; }

say "apt-get install ./$(basename "$deb") pocl-opencl-icd man-db"
in_root "cd /tmp && apt-get update -qq && apt-get install -y -q ./$(basename "$deb") pocl-opencl-icd man-db" \
  >"$root/tmp/apt.log" 2>&1 || { tail -n 30 "$root/tmp/apt.log" >&2; exit 1; }
grep -E '^(Need to get|After this operation|[0-9]+ upgraded)' "$root/tmp/apt.log" >&2 || true
in_root 'dpkg-query -W -f="installed: \${Package} \${Version}, Installed-Size \${Installed-Size} KiB\n" clmarch pocl-opencl-icd' >&2
in_root 'echo "Debian $(cat /etc/debian_version); the largest packages installed (KiB):" &&
  dpkg-query -W -f="\${Installed-Size} \${Package}\n" | sort -rn | head -n 8' >&2

say "clmarch --version"
in_root 'clmarch --version'
say "clmarch devices"
in_root 'clmarch devices'
say "clmarch render /usr/share/clmarch/scenes/torus.yaml -o /tmp/t.png"
in_root 'time clmarch render /usr/share/clmarch/scenes/torus.yaml -o /tmp/t.png && test -s /tmp/t.png &&
  echo "/tmp/t.png: $(stat -c %s /tmp/t.png) bytes"'
cp "$root/tmp/t.png" build-package/package-check-torus.png
say "the bash completion of 'clmarch render --sa'"
in_root 'source /usr/share/bash-completion/completions/clmarch && COMP_WORDS=(clmarch render --sa) COMP_CWORD=2 &&
  _clmarch && [ "${COMPREPLY[*]}" = --samples ] && echo "COMPREPLY: ${COMPREPLY[*]}"'
say "man clmarch"
in_root 'MANPAGER=cat MANWIDTH=80 man clmarch 2>&1 | head -n 12'
say "passed: the package installs on Debian $(cat "$root/etc/debian_version") and renders (build-package/package-check-torus.png)"

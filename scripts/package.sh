#!/usr/bin/env bash
# Builds the Debian package of clmarch: a Release build without tests in build-package/, installed
# under /usr by `cpack -G DEB` (cmake/package.cmake; dpkg-shlibdeps computes Depends). Prints the
# path of build-package/clmarch_VERSION_ARCH.deb. Arguments go to cmake, e.g. -DCLMARCH_MPI=OFF for
# a package without Open MPI among its dependencies.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache keys paths relative to the checkout, so that another clone reuses what this one compiled.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
# Debian's hardening flags (dpkg-buildflags: fortified functions, stack protector, relro and bindnow),
# as a package built by debhelper has them; the Release flags follow them (-O3 wins over -O2).
export DEB_BUILD_MAINT_OPTIONS=hardening=+all
cmake -S . -B build-package -G Ninja -DCMAKE_BUILD_TYPE=Release -DCLMARCH_BUILD_TESTS=OFF -DCLMARCH_PYTHON=OFF \
  -DCMAKE_INSTALL_PREFIX=/usr "-DCMAKE_CXX_FLAGS=$(dpkg-buildflags --get CPPFLAGS) $(dpkg-buildflags --get CXXFLAGS)" \
  "-DCMAKE_EXE_LINKER_FLAGS=$(dpkg-buildflags --get LDFLAGS)" "$@" >/dev/null
cmake --build build-package >&2
rm -f build-package/clmarch_*.deb
if ! (cd build-package && cpack -G DEB) >build-package/cpack.log 2>&1; then
  cat build-package/cpack.log >&2
  exit 1
fi
debs=(build-package/clmarch_*.deb)
if [ ${#debs[@]} -ne 1 ] || [ ! -f "${debs[0]}" ]; then
  echo "package.sh: cpack wrote no single clmarch_*.deb in build-package/" >&2
  exit 1
fi
echo "$PWD/${debs[0]}"

#!/usr/bin/env bash
# Installs what clmarch needs from Debian's packages, skipping what is present. Run as root (or
# with sudo available); safe to run again. clang and libclang-rt-14-dev (libFuzzer and clang's
# sanitizer runtimes) are for scripts/fuzz.sh; libopenmpi-dev and openmpi-bin let `clmarch render`
# run under mpirun (docs/cli.md#mpi); python3 runs scripts/large-scene.py, whose scenes the tests
# check; python3-dev, pybind11-dev, python3-numpy, python3-pytest and python3-openimageio (an EXR
# reader independent of the writer) build and test the Python module (python/, docs/python.md).
# libtinygltf-dev writes the glTF binary meshes of `clmarch mesh` (host/mesh/); libassimp-dev is the
# tests' reader of every mesh format, independent of the writers; libcpp-httplib-dev serves
# `clmarch preview`, and nodejs runs its page's script in the tests; chromium, chromium-driver and
# python3-selenium load that page in a real, headless browser for the tests (ctest PreviewBrowser)
# and for scripts/preview-bench.py --browser. glslang-dev parses and type-checks users' GLSL (the
# glsl node, host/glsl/); glslang-tools only because glslang-dev's CMake package names its
# glslangValidator, and find_package(glslang) fails on a machine without it.
# clang-format and clang-tidy serve scripts/format.sh and scripts/tidy.sh. groff-base lets the
# tests render the man page (dpkg-dev, which scripts/package.sh needs, comes with build-essential).
# `setup.sh --plots` also installs python3-matplotlib for scripts/sweep-plot.py (run it with
# /usr/bin/python3); `setup.sh --peers` the GLSL peer's libraries (EGL, OSMesa, libpng, Mesa's
# llvmpipe) for scripts/speed-vs-peers.sh; `setup.sh --shells` adds zsh and fish, whose completion
# files the tests then check too, `setup.sh --package-check` debootstrap and lintian for
# scripts/package-check.sh, `setup.sh --mandelbulber` Mandelbulber2 (2.20 in Debian 12), the
# peer whose voxel export scripts/mesh-vs-mandelbulber.sh times against `clmarch mesh`, and
# `setup.sh --povray` POV-Ray, which renders the meshes' pictures headless (scripts/mesh-pictures.sh).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  libglm-dev libopenimageio-dev openimageio-tools
  libyaml-cpp-dev libcli11-dev libfmt-dev nlohmann-json3-dev libtbb-dev
  libgtest-dev libbenchmark-dev libmuparser-dev
  clang libclang-rt-14-dev clang-format clang-tidy
  libopenmpi-dev openmpi-bin
  python3 python3-dev python3-numpy python3-pytest pybind11-dev python3-openimageio groff-base
  libtinygltf-dev libassimp-dev libcpp-httplib-dev nodejs chromium chromium-driver python3-selenium
  glslang-dev glslang-tools
)
for arg in "$@"; do
  case "$arg" in
    --plots) packages+=(python3-matplotlib) ;;
    --peers) packages+=(libegl-dev libosmesa6-dev libpng-dev libgl1-mesa-dri) ;;
    --shells) packages+=(zsh fish) ;;
    --package-check) packages+=(debootstrap lintian) ;;
    --mandelbulber) packages+=(mandelbulber2) ;;
    --povray) packages+=(povray) ;;
    *) echo "setup.sh: unknown option $arg (expected --plots, --peers, --shells, --package-check, --mandelbulber or --povray)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup.sh: run as root to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "setup.sh: installing ${missing[*]}" >&2
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null

#!/usr/bin/env bash
# Installs the Debian (bookworm) packages Talus needs to build, test and run.
# Idempotent: when every package is already installed it does nothing, so reruns are fast.
# Runs apt-get as root, or through sudo when not root and sudo exists.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build git pkg-config
  # OpenCL: ICD loader, headers, the PoCL CPU device (used in CI), clinfo for diagnostics
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo
  # raster I/O and linear algebra
  libgdal-dev gdal-bin libeigen3-dev
  # desktop application (Qt 5 + OpenGL; Mesa's llvmpipe gives OpenGL 3.3 core without a GPU)
  qtbase5-dev libqt5opengl5-dev libglew-dev libgl1-mesa-dri
  # tests, headless display for GUI tests (mesa-utils: glxinfo, to check the OpenGL version;
  # x11-utils: xwininfo, with which a GUI test finds the program's message box)
  libgtest-dev googletest xvfb xauth mesa-utils x11-utils
  # scene tools (tools/make_example_scene.py)
  python3 python3-numpy python3-gdal
  # fuzzing (tools/fuzz.sh): clang with libFuzzer and the sanitizer runtimes; llvm-symbolizer
  # (llvm-14) for readable sanitizer reports
  clang-14 libclang-rt-14-dev llvm-14
  # ensembles across ranks (talus ensemble under mpirun; optional, docs/ensembles.md)
  openmpi-bin libopenmpi-dev
)

missing=()
for pkg in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "installed" ]]; then
    missing+=("$pkg")
  fi
done

if (( ${#missing[@]} == 0 )); then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

echo "setup: installing ${#missing[@]} missing package(s): ${missing[*]}"
as_root=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
  else
    echo "setup: not root and sudo is not available; install these packages as root:" >&2
    echo "  apt-get install ${missing[*]}" >&2
    exit 1
  fi
fi

"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y --no-install-recommends "${missing[@]}"
echo "setup: done"

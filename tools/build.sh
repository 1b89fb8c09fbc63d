#!/usr/bin/env bash
# Configures (Ninja, Release) and builds Talus.
# Build directory: build/ at the repository root, or $TALUS_BUILD_DIR (relative paths are
# taken from the repository root). Extra arguments go to the CMake configure step,
# e.g. bash tools/build.sh -DTALUS_BUILD_GUI=OFF
# The desktop application (gui/) is built when Qt 5 Widgets is installed (tools/setup.sh installs it).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${TALUS_BUILD_DIR:-build}
[[ "$build_dir" = /* ]] || build_dir="$root/$build_dir"

gui=OFF
if pkg-config --exists Qt5Widgets 2>/dev/null; then gui=ON; fi

cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTALUS_BUILD_GUI="$gui" "$@"
cmake --build "$build_dir" -j "$(nproc)"

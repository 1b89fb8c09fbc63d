#!/usr/bin/env bash
# Configures (Ninja, Release) and builds Talus.
# Build directory: build/ at the repository root, or $TALUS_BUILD_DIR (relative paths are
# taken from the repository root). Extra arguments go to the CMake configure step,
# e.g. bash tools/build.sh -DTALUS_BUILD_GUI=ON
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${TALUS_BUILD_DIR:-build}
[[ "$build_dir" = /* ]] || build_dir="$root/$build_dir"

cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$build_dir" -j "$(nproc)"

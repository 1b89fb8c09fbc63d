#!/usr/bin/env bash
# Sets up, builds and runs the example scene: a dam break over real terrain
# (data/kot_dambreak, a crop of AvaFrame's avaKot DEM). Results go to out/kot_dambreak.
# Extra arguments go to `talus run`, e.g. bash tools/run_example.sh --precision double
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
build_dir=${TALUS_BUILD_DIR:-build}
[[ "$build_dir" = /* ]] || build_dir="$root/$build_dir"
export TALUS_BUILD_DIR="$build_dir"

bash tools/setup.sh
bash tools/build.sh

"$build_dir/src/talus" run data/kot_dambreak/kot_dambreak.run --out out/kot_dambreak --overwrite "$@"
echo "example: results in $root/out/kot_dambreak"

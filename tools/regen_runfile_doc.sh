#!/usr/bin/env bash
# Regenerates the key table at the end of docs/runfile.md from the key declarations
# (src/sim/RunKeys.cpp) with `talus keys --markdown`. Run after adding or changing a key.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
talus=${TALUS_BUILD_DIR:-$root/build}/src/talus
doc=$root/docs/runfile.md
head=$(grep -n '^## Keys$' "$doc" | cut -d: -f1)
{ head -n "$head" "$doc"; echo; "$talus" keys --markdown; } > "$doc.tmp"
mv "$doc.tmp" "$doc"
echo "updated $doc"

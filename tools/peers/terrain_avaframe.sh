#!/usr/bin/env bash
# Talus vs AvaFrame com1DFA (Coulomb, mu = tan 25 deg = 0.4663) on the AvaFrame terrain cases
# (issue 13, part 5). Re-runnable; everything it writes goes under $WORK (default /work/terrain_peers).
#
#   tools/peers/terrain_avaframe.sh [CASE ...]        # default: avaKot avaAlr
#
# Environment:
#   VENV   AvaFrame virtual environment (default /work/avaframe-venv; created with `pip install avaframe`)
#   WORK   output folder (default /work/terrain_peers)
#   DATA   terrain data (default /work/shared/data/terrain)
#   TALUS  talus binary (default: the first executable `talus` under build/)
#   NICE   prefix for the heavy commands (default "nice -n 19")
#   MD     write the Markdown table also to this file (optional)
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
VENV="${VENV:-/work/avaframe-venv}"
WORK="${WORK:-/work/terrain_peers}"
DATA="${DATA:-/work/shared/data/terrain}"
NICE="${NICE:-nice -n 19}"
TALUS="${TALUS:-$(find "$ROOT/build" -name talus -type f -perm -u+x | head -n 1)}"
CASES=("$@")
[ ${#CASES[@]} -gt 0 ] || CASES=(avaKot avaAlr)

if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import avaframe" 2>/dev/null; then
  python3 -m venv "$VENV"
  $NICE "$VENV/bin/pip" install -q avaframe
fi
PY="$VENV/bin/python"
[ -x "$TALUS" ] || { echo "no talus binary (set TALUS)" >&2; exit 1; }
mkdir -p "$WORK"
{ date -u; echo "talus: $TALUS"; sha256sum "$TALUS"; git -C "$ROOT" rev-parse HEAD 2>/dev/null || true
  "$PY" -c "import importlib.metadata as m; print('avaframe', m.version('avaframe'))"; } > "$WORK/provenance.txt"

for c in "${CASES[@]}"; do
  echo "== $c: AvaFrame com1DFA"
  $NICE "$PY" "$HERE/terrain_avaframe_run.py" "$DATA/$c" "$WORK" > "$WORK/avaframe_$c.log" 2>&1 \
    || { echo "AvaFrame failed on $c, see $WORK/avaframe_$c.log" >&2; tail -n 20 "$WORK/avaframe_$c.log" >&2; }
  echo "== $c: Talus"
  "$PY" "$HERE/terrain_compare.py" prep "$DATA/$c" "$WORK"
  ( cd "$WORK/talus/$c" && $NICE "$TALUS" run case.run --out out --precision double --overwrite --quiet ) \
    > "$WORK/talus_$c.log" 2>&1 \
    || { echo "Talus failed on $c (rc $?), see $WORK/talus_$c.log" >&2; tail -n 20 "$WORK/talus_$c.log" >&2; }
done

"$PY" "$HERE/terrain_compare.py" table "$WORK" "${CASES[@]}" --data "$DATA" ${MD:+--md "$MD"}

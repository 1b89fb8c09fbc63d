#!/usr/bin/env bash
# Talus vs AvaFrame com1DFA (Coulomb, mu = tan 25 deg = 0.4663) on the AvaFrame terrain cases
# (issue 13, part 5), or with Voellmy friction (FRICTION=voellmy, issue 19 item 4).
# Re-runnable; everything it writes goes under $WORK (default /work/terrain_peers).
#
#   tools/peers/terrain_avaframe.sh [CASE ...]        # default: avaKot avaAlr (also: avaHelix)
#
# Environment:
#   VENV   AvaFrame virtual environment (default /work/avaframe-venv; created with `pip install avaframe`)
#   WORK   output folder (default /work/terrain_peers)
#   DATA   terrain data (default /work/shared/data/terrain)
#   TALUS  talus binary (default: the first executable `talus` under build/)
#   NICE   prefix for the heavy commands (default "nice -n 19")
#   MD     write the Markdown table also to this file (optional)
#   SKIP_AVAFRAME=1  reuse $WORK/avaframe/<case> when its run_info.json exists (no com1DFA rerun)
#   TALUS_SET  extra Talus settings, ';'-separated, each passed as --set (e.g. "Limiter=minmod");
#              the run then goes to talus/<case>/out_<label> (label: TALUS_SET with characters other
#              than A-Za-z0-9.,- as '_', or TALUS_LABEL) and the table shows every out* folder
#   FRICTION   coulomb (default, unchanged) or voellmy: com1DFA with frictModel = Voellmy and
#              AvaFrame's own muvoellmy / xsivoellmy (read from the installed com1DFACfg.ini), tEnd
#              400 s (AvaFrame's default) with its stop criterion; Talus with Solid Rheology=voellmy,
#              the same Voellmy Mu / Voellmy Xi, End Time 400 s, Stop At Rest Fraction=0.01 (the
#              same kinetic-energy criterion as com1DFA's stopCrit = 0.01), Initial Solid Density 200.
#              Use a separate WORK (default for voellmy: /work/voellmy_peers).
#   VOELLMY_MU, VOELLMY_XI  override AvaFrame's standard values (both codes)
#   PATHS      folder with <case>/path_aimec.shp (AvaFrame's AIMEC path lines): the table then also
#              gives the runout along that path (optional; needed for a meaningful avaHelix runout)
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
VENV="${VENV:-/work/avaframe-venv}"
FRICTION="${FRICTION:-coulomb}"
case "$FRICTION" in
  coulomb) WORK="${WORK:-/work/terrain_peers}" ;;
  voellmy) WORK="${WORK:-/work/voellmy_peers}" ;;
  *) echo "FRICTION must be coulomb or voellmy" >&2; exit 1 ;;
esac
DATA="${DATA:-/work/shared/data/terrain}"
NICE="${NICE:-nice -n 19}"
TALUS="${TALUS:-$(find "$ROOT/build" -name talus -type f -perm -u+x | head -n 1)}"
SETS=()
LABEL=""
if [ -n "${TALUS_SET:-}" ]; then
  IFS=';' read -ra KV <<< "$TALUS_SET"
  for kv in "${KV[@]}"; do SETS+=(--set "$kv"); done
  LABEL="${TALUS_LABEL:-$(printf '%s' "$TALUS_SET" | tr -c 'A-Za-z0-9.,-' '_')}"
fi
OUT="out${LABEL:+_$LABEL}"
CASES=("$@")
[ ${#CASES[@]} -gt 0 ] || CASES=(avaKot avaAlr)

if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import avaframe" 2>/dev/null; then
  python3 -m venv "$VENV"
  $NICE "$VENV/bin/pip" install -q avaframe
fi
PY="$VENV/bin/python"
AVA_ARGS=()
PREP_ARGS=()
if [ "$FRICTION" = voellmy ]; then
  # AvaFrame's standard Voellmy parameters, from the installed package's own default ini
  read -r MU_D XI_D < <("$PY" -c "import sys; sys.path.insert(0, '$HERE'); import terrain_avaframe_run as t; d = t.avaframe_defaults(); print(float(d['muvoellmy']), float(d['xsivoellmy']))")
  VMU="${VOELLMY_MU:-$MU_D}"; VXI="${VOELLMY_XI:-$XI_D}"
  AVA_ARGS=(--friction voellmy --mu-voellmy "$VMU" --xi-voellmy "$VXI" --tend 400)
  PREP_ARGS=(--rheology voellmy --voellmy-mu "$VMU" --voellmy-xi "$VXI" --tend-s 400 --stop-fraction 0.01 --density 200)
fi
[ -x "$TALUS" ] || { echo "no talus binary (set TALUS)" >&2; exit 1; }
mkdir -p "$WORK"
{ date -u; echo "talus: $TALUS"; sha256sum "$TALUS"; git -C "$ROOT" rev-parse HEAD 2>/dev/null || true
  echo "talus settings: ${TALUS_SET:-(defaults)}"
  echo "friction: $FRICTION ${AVA_ARGS[*]+${AVA_ARGS[*]}}"
  "$PY" -c "import importlib.metadata as m; print('avaframe', m.version('avaframe'))"; } > "$WORK/provenance${LABEL:+_$LABEL}.txt"

for c in "${CASES[@]}"; do
  if [ "${SKIP_AVAFRAME:-0}" = 1 ] && [ -f "$WORK/avaframe/$c/run_info.json" ]; then
    echo "== $c: AvaFrame com1DFA (reusing $WORK/avaframe/$c)"
  else
    echo "== $c: AvaFrame com1DFA"
    $NICE "$PY" "$HERE/terrain_avaframe_run.py" "$DATA/$c" "$WORK" ${AVA_ARGS[@]+"${AVA_ARGS[@]}"} > "$WORK/avaframe_$c.log" 2>&1 \
      || { echo "AvaFrame failed on $c, see $WORK/avaframe_$c.log" >&2; tail -n 20 "$WORK/avaframe_$c.log" >&2; }
  fi
  echo "== $c: Talus ${TALUS_SET:-}"
  "$PY" "$HERE/terrain_compare.py" prep "$DATA/$c" "$WORK" ${PREP_ARGS[@]+"${PREP_ARGS[@]}"}
  LOG="$WORK/talus_$c${LABEL:+_$LABEL}.log"
  ( cd "$WORK/talus/$c" && $NICE "$TALUS" run case.run --out "$OUT" --precision double --overwrite --quiet ${SETS[@]+"${SETS[@]}"} ) \
    > "$LOG" 2>&1 || { echo "Talus failed on $c (rc $?), see $LOG" >&2; tail -n 20 "$LOG" >&2; }
done

"$PY" "$HERE/terrain_compare.py" table "$WORK" "${CASES[@]}" --data "$DATA" ${MD:+--md "$MD"} ${PATHS:+--paths "$PATHS"}

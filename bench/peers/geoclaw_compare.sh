#!/usr/bin/env bash
# Side-by-side comparison of Talus with GeoClaw (clawpack 5.x) for water: kot_dambreak at 5 m,
# a grid study (10 / 5 / 2.5 m) and the Ritter dam break. See bench/peers/README.md.
#
# usage: bash bench/peers/geoclaw_compare.sh [--quick] [--fresh] [--only STEPS]
#   --quick        each timing case once, no 2.5 m grid
#   --fresh        forget the runs recorded in $PEERS_WORK/runs.jsonl (otherwise a rerun resumes)
#   --only STEPS   comma list of: setup,prepare,kot,grid,ritter,plane,rough,roll,dem,report (default: all,
#                  in order; plane = the steep-plane diagnostic, steep_plane.py, a few seconds; rough = the
#                  rough-slope grid study, rough_slope.py, about 2 minutes; roll = roll waves on a steep
#                  plane, roll_waves.py, about 2 minutes; dem = the grid study of a second real DEM,
#                  dem_study.py, about 25 minutes, its own table in $PEERS_WORK/results_<case>.md)
#
# environment:
#   PEERS_VENV   Python virtual environment (default /work/clawpack-venv)
#   PEERS_WORK   work directory (default /work/peers_geoclaw)
#   CLAWPACK_VERSION (default 5.14.0), PEERS_FFLAGS (default "-O2 -fopenmp")
#   PEERS_LEVELS grid-study resolutions in m (default 10,5,2.5; --quick: 10,5)
#   PEERS_RITTER_DX (default 1,0.5,0.25), PEERS_REPS (default 3; --quick: 1)
#   TALUS_BIN    Talus executable to time (default: a snapshot copy of build/src/talus)
#   PEERS_GRID_TALUS_CONFIG  Talus configuration of the grid study (default float_sc0)
#   PEERS_DEM_CASE  scene of the dem step (default data/alr_dambreak); PEERS_DEM_LEVELS Talus grids
#                (default 5,2.5,1.25); PEERS_DEM_GEOCLAW_LEVELS GeoClaw grids (default 5,2.5)
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
VENV="${PEERS_VENV:-/work/clawpack-venv}"
WORK="${PEERS_WORK:-/work/peers_geoclaw}"
CLAWV="${CLAWPACK_VERSION:-5.14.0}"
FFLAGS_GC="${PEERS_FFLAGS:--O2 -fopenmp}"
QUICK=0
FRESH=0
ONLY="setup,prepare,kot,grid,ritter,plane,rough,roll,dem,report"

while [ $# -gt 0 ]; do
  case "$1" in
    --quick) QUICK=1 ;;
    --fresh) FRESH=1 ;;
    --only) ONLY="$2"; shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "unknown argument: $1" >&2; exit 2 ;;
  esac
  shift
done
if [ "$QUICK" = 1 ]; then
  LEVELS="${PEERS_LEVELS:-10,5}"; REPS="${PEERS_REPS:-1}"
else
  LEVELS="${PEERS_LEVELS:-10,5,2.5}"; REPS="${PEERS_REPS:-3}"
fi
RITTER_DX="${PEERS_RITTER_DX:-1,0.5,0.25}"
want() { case ",$ONLY," in *",$1,"*) return 0 ;; *) return 1 ;; esac; }
log() { echo "[peers $(date +%H:%M:%S)] $*" >&2; }

mkdir -p "$WORK"
PY="$VENV/bin/python"
CLAW="$WORK/src/clawpack-$CLAWV"
EXE="$WORK/build/xgeoclaw"
export OMP_NUM_THREADS=1

# ------------------------------------------------------------------------------------------------
if want setup; then
  # Python environment: Debian's python3 carries numpy and GDAL's bindings; the venv sees them.
  if [ ! -x "$PY" ]; then
    BASEPY=/usr/bin/python3; [ -x "$BASEPY" ] || BASEPY="$(command -v python3)"
    log "creating venv $VENV (with system site packages, from $BASEPY)"
    "$BASEPY" -m venv --system-site-packages "$VENV"
  fi
  if ! "$PY" -c "import numpy" 2>/dev/null; then "$PY" -m pip install -q numpy; fi
  if ! "$PY" -c "import clawpack, importlib.metadata as m; assert m.version('clawpack') == '$CLAWV'" 2>/dev/null; then
    log "pip install clawpack==$CLAWV"
    "$PY" -m pip install -q "clawpack==$CLAWV"
  fi
  # The wheel holds the Python modules only; GeoClaw's Fortran sources come from the sdist.
  if [ ! -f "$CLAW/geoclaw/src/2d/shallow/Makefile.geoclaw" ]; then
    mkdir -p "$WORK/src"
    if [ ! -f "$WORK/src/clawpack-$CLAWV.tar.gz" ]; then
      log "pip download clawpack==$CLAWV (source distribution)"
      "$PY" -m pip download -q "clawpack==$CLAWV" --no-deps --no-binary clawpack -d "$WORK/src"
    fi
    tar -xzf "$WORK/src/clawpack-$CLAWV.tar.gz" -C "$WORK/src"
  fi
  # GeoClaw's standard single-layer executable (the same for every case: cases differ in *.data)
  if [ ! -x "$EXE" ] || [ "$(cat "$WORK/build/fflags" 2>/dev/null)" != "$FFLAGS_GC" ]; then
    log "building xgeoclaw (gfortran $FFLAGS_GC)"
    mkdir -p "$WORK/build"
    cat > "$WORK/build/Makefile" <<'EOF'
# Written by bench/peers/geoclaw_compare.sh: GeoClaw's standard 2D shallow-water executable.
CLAWMAKE = $(CLAW)/clawutil/src/Makefile.common
CLAW_PKG = geoclaw
EXE = xgeoclaw
SETRUN_FILE = setrun.py
OUTDIR = _output
GEOLIB = $(CLAW)/geoclaw/src/2d/shallow
include $(GEOLIB)/Makefile.geoclaw
EXCLUDE_MODULES =
EXCLUDE_SOURCES =
MODULES =
SOURCES = \
  $(CLAW)/riemann/src/rpn2_geoclaw.f \
  $(CLAW)/riemann/src/rpt2_geoclaw.f \
  $(CLAW)/riemann/src/geoclaw_riemann_utils.f
include $(CLAWMAKE)
EOF
    ( cd "$WORK/build" && CLAW="$CLAW" CLAW_PYTHON="$PY" FC=gfortran FFLAGS="$FFLAGS_GC" \
        make new > make.log 2>&1 ) || { tail -30 "$WORK/build/make.log"; exit 1; }
    echo "$FFLAGS_GC" > "$WORK/build/fflags"
  fi
  # Talus: time a snapshot of the binary, so a rebuild of build/ during the study changes nothing
  if [ -z "${TALUS_BIN:-}" ]; then
    [ -x "$REPO/build/src/talus" ] || { echo "no $REPO/build/src/talus: build Talus first" >&2; exit 1; }
    mkdir -p "$WORK/bin"
    cp "$REPO/build/src/talus" "$WORK/bin/talus.new" && mv "$WORK/bin/talus.new" "$WORK/bin/talus"
    ( cd "$REPO" && git rev-parse --short HEAD 2>/dev/null || echo unknown ) > "$WORK/bin/talus.commit"
    ( cd "$REPO" && git status --porcelain -- src kernels 2>/dev/null | head -c 1 | wc -c ) > "$WORK/bin/talus.dirty"
  fi
  "$PY" - "$WORK" "$CLAWV" "$FFLAGS_GC" "${TALUS_BIN:-$WORK/bin/talus}" <<'EOF'
import json, os, platform, subprocess, sys
work, clawv, fflags, talus = sys.argv[1:5]
def sh(c):
    try: return subprocess.run(c, shell=True, capture_output=True, text=True).stdout.strip()
    except Exception: return ""
env = dict(clawpack=clawv, fflags=fflags, talus_bin=talus,
           git_commit=open(os.path.join(work, "bin", "talus.commit")).read().strip() if os.path.exists(os.path.join(work, "bin", "talus.commit")) else "unknown",
           git_dirty=open(os.path.join(work, "bin", "talus.dirty")).read().strip() not in ("", "0") if os.path.exists(os.path.join(work, "bin", "talus.dirty")) else False,
           gfortran=sh("gfortran --version | head -1"), talus_device=sh(f"'{talus}' devices | head -1"),
           machine=f"{sh('getconf _NPROCESSORS_ONLN')} cores, " + sh("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2").strip() + f", {platform.platform()}")
json.dump(env, open(os.path.join(work, "environment.json"), "w"), indent=1)
EOF
fi
export TALUS_BIN="${TALUS_BIN:-$WORK/bin/talus}"
export GEOCLAW_EXE="$EXE"
export CLAW

if [ "$FRESH" = 1 ] && [ -f "$WORK/runs.jsonl" ]; then
  mv "$WORK/runs.jsonl" "$WORK/runs.jsonl.$(date +%Y%m%d%H%M%S)"
fi

# ------------------------------------------------------------------------------------------------
if want prepare; then
  log "preparing grids ($LEVELS m) and Ritter cases (dx $RITTER_DX m)"
  "$PY" "$HERE/geoclaw_cases.py" grids "$REPO" "$WORK" --levels "$LEVELS" | grep -v '^ \|^---\|^$\|fgmax grid' >&2
  "$PY" "$HERE/geoclaw_cases.py" ritter "$WORK" --dx "$RITTER_DX" | grep -v '^ \|^---\|^$\|fgmax grid' >&2
fi

# POCL_MAX_PTHREAD_COUNT=1 must give PoCL one compute unit (checked, since it is PoCL-version specific)
if want kot || want grid || want ritter; then
  cu1="$(POCL_MAX_PTHREAD_COUNT=1 "$TALUS_BIN" devices | head -1)"
  cu="$("$TALUS_BIN" devices | head -1)"
  log "Talus device: $cu"
  log "with POCL_MAX_PTHREAD_COUNT=1: $cu1"
fi
if want kot;    then log "kot_dambreak 5 m ($REPS rounds)"; "$PY" "$HERE/peers_run.py" kot "$WORK" --reps "$REPS"; fi
if want grid;   then log "grid study ($LEVELS m)"; "$PY" "$HERE/peers_run.py" grid "$WORK" --reps "$REPS" --levels "$LEVELS"; fi
if want ritter; then log "Ritter (dx $RITTER_DX m)"; "$PY" "$HERE/peers_run.py" ritter "$WORK" --reps "$REPS" --dx "$RITTER_DX"; fi
if want plane;  then log "steep-plane diagnostic"; "$PY" "$HERE/steep_plane.py" "$WORK" > /dev/null; fi
if want rough;  then log "rough-slope grid study"; "$PY" "$HERE/rough_slope.py" "$WORK" > /dev/null; fi
if want roll;   then log "roll waves on a steep plane"; "$PY" "$HERE/roll_waves.py" "$WORK" > /dev/null; fi
if want dem;    then
  log "second real DEM: ${PEERS_DEM_CASE:-$REPO/data/alr_dambreak}"
  "$PY" "$HERE/dem_study.py" "${PEERS_DEM_CASE:-$REPO/data/alr_dambreak}" "$WORK" \
    --talus-levels "${PEERS_DEM_LEVELS:-5,2.5,1.25}" --geoclaw-levels "${PEERS_DEM_GEOCLAW_LEVELS:-5,2.5}"
fi
if want report; then "$PY" "$HERE/compare_maps.py" "$WORK"; log "written $WORK/results.md"; fi

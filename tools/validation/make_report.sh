#!/usr/bin/env bash
# Regenerates the validation report docs/validation.md and its figures in docs/images/validation/.
#
#   bash tools/validation/make_report.sh [--quick] [--no-build] [--report-only]
#
# 1. builds Talus (tools/build.sh into build/, or an existing build folder named by TALUS_BUILD_DIR);
# 2. runs the verification tests of spec §10 with TALUS_VALIDATION_OUT=out/validation, so they
#    write their profiles and errors as CSV (tests/verification/ValidationOut.hpp);
# 3. runs the example and paper scenes (data/kot_*, data/block_slide, data/paper_*) into
#    out/validation/scenes/NAME, each under a wall-time budget (`timeout`): a run that exceeds it is
#    cut, and the report says at which simulated time (the last row of its diagnostics.csv);
# 4. plots the profiles (tools/validation/plots.py, matplotlib), renders the scenes' maps with
#    `talus render` and writes docs/validation.md from tools/validation/template.md
#    (tools/validation/report.py), appending docs/validation_parts/*.md in name order.
#
# --quick: the fast scenes only (the flumes need hours on a CPU), a budget of 120 s per scene, and
#          the column-collapse series is not rerun (its CSVs from an earlier full run are reused).
# --no-build: use the binaries already in the build folder.
# --report-only: no build, tests or scenes: redraw the figures and rewrite docs/validation.md from the
#          files of the last run in out/validation (e.g. after a docs/validation_parts/*.md changed).
# Budget per scene: TALUS_SCENE_BUDGET seconds (default 120 with --quick, 600 otherwise).
# Needs python3 with matplotlib and numpy: installed with apt (python3-matplotlib) when missing.
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cd "$root"
quick=0
build=1
report_only=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    --no-build) build=0 ;;
    --report-only) build=0; report_only=1 ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "make_report.sh: unknown option '$arg' (--quick, --no-build, --report-only)" >&2; exit 1 ;;
  esac
done
mode=$([[ $quick = 1 ]] && echo quick || echo full)
out="$root/out/validation"
if [[ $report_only = 1 ]]; then
  mode=$(cat "$out/mode.txt" 2>/dev/null || echo "$mode")
fi
t_start=$(date +%s)

# ---- 1. build ---------------------------------------------------------------------------------
build_dir=${TALUS_BUILD_DIR:-build}
[[ "$build_dir" = /* ]] || build_dir="$root/$build_dir"
if [[ $build = 1 ]]; then
  if [[ -n "${TALUS_BUILD_DIR:-}" && -f "$build_dir/build.ninja" ]]; then
    echo "== building in $build_dir"
    cmake --build "$build_dir" -j "$(nproc)" --target talus talus_verification_tests || exit 1
  else
    echo "== building with tools/build.sh into $build_dir"
    TALUS_BUILD_DIR="$build_dir" bash tools/build.sh || exit 1
  fi
fi
talus="$build_dir/src/talus"
tests="$build_dir/tests/talus_verification_tests"
for f in "$talus" "$tests"; do
  [[ -x "$f" ]] || { echo "make_report.sh: $f not found (build first, or set TALUS_BUILD_DIR)" >&2; exit 1; }
done

# ---- python with matplotlib -------------------------------------------------------------------
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
if ! "$py" -c 'import matplotlib, numpy' 2>/dev/null; then
  echo "== installing python3-matplotlib with apt"
  sudo=""
  [[ $(id -u) = 0 ]] || sudo=sudo
  $sudo apt-get install -y --no-install-recommends python3-matplotlib python3-numpy ||
    { $sudo apt-get update && $sudo apt-get install -y --no-install-recommends python3-matplotlib python3-numpy; } ||
    { echo "make_report.sh: cannot install python3-matplotlib" >&2; exit 1; }
  py=/usr/bin/python3
fi

# ---- 2. verification tests ----------------------------------------------------------------------
mkdir -p "$out"
if [[ $report_only = 0 ]]; then
echo "$mode" > "$out/mode.txt"
if [[ $quick = 1 ]]; then
  find "$out" -maxdepth 1 -name '*.csv' ! -name 'column_*' -delete
else
  find "$out" -maxdepth 1 -name '*.csv' -delete
fi
rm -f "$out"/gtest*.json
filter='DamBreak.*:Thacker.*:WellBalanced.*:Granular.*:ParticleBlock.*:ParticleDamBreak.*:ParticleCut.*:Conservation.*'
echo "== verification tests ($filter), CSVs into $out"
t0=$(date +%s)
TALUS_VALIDATION_OUT="$out" "$tests" --gtest_filter="$filter" --gtest_output="json:$out/gtest.json" \
  > "$out/verification.log" 2>&1
echo "   exit status $? in $(( $(date +%s) - t0 )) s (log: $out/verification.log)"
grep -E '^\[  (PASSED|FAILED)  \]' "$out/verification.log" | head -20
# The column-collapse series (Lube et al. 2005) is long: its own run, under a budget
# (TALUS_COLLAPSE_BUDGET seconds, default 1800), so a slow machine still gets the rest of the report.
if [[ $quick = 0 ]]; then
  echo "== column collapse (ColumnCollapse.*)"
  t0=$(date +%s)
  TALUS_VALIDATION_OUT="$out" timeout "${TALUS_COLLAPSE_BUDGET:-1800}" "$tests" --gtest_filter='ColumnCollapse.*' \
    --gtest_output="json:$out/gtest_column_collapse.json" > "$out/column_collapse.log" 2>&1
  echo "   exit status $? in $(( $(date +%s) - t0 )) s (log: $out/column_collapse.log)"
fi

# ---- 3. scenes -----------------------------------------------------------------------------------
budget=${TALUS_SCENE_BUDGET:-$([[ $quick = 1 ]] && echo 120 || echo 600)}
scenes=(kot_dambreak kot_debrisflow block_slide paper_setup1_A paper_setup1_B paper_setup1_C
        paper_setup2_A paper_setup2_B paper_setup2_C paper_flume_c26 paper_flume_c18)
rm -rf "$out/scenes"
for s in "${scenes[@]}"; do
  dir="$out/scenes/$s"
  run_file="$root/data/$s/$s.run"
  mkdir -p "$dir"
  if [[ ! -f "$run_file" ]]; then
    printf 'status=skipped\nreason=no run file %s\n' "$run_file" > "$dir/status.txt"
    continue
  fi
  if [[ $quick = 1 && $s = paper_flume_* ]]; then
    printf 'status=skipped\nreason=quick mode: the flume needs hours on a CPU, run without --quick\nrun_file=%s\n' \
      "$run_file" > "$dir/status.txt"
    continue
  fi
  echo "== scene $s (budget $budget s)"
  t0=$(date +%s.%N)
  timeout --signal=TERM "$budget" "$talus" run "$run_file" --out "$dir" --overwrite --quiet > "$dir/talus.log" 2>&1
  rc=$?
  wall=$(awk -v a="$(date +%s.%N)" -v b="$t0" 'BEGIN { printf "%.1f", a - b }')
  case $rc in
    0) status=completed ;;
    124) status=cut ;;
    *) status=failed ;;
  esac
  # The diagnosis of a failed run: talus's first own message line (with --quiet there is no progress).
  message=$(grep -E '^talus: ' "$dir/talus.log" | grep -v 'maps and diagnostics written' | head -n1 | cut -c1-400)
  printf 'status=%s\nexit=%s\nwall_s=%.1f\nbudget_s=%s\nrun_file=%s\nmessage=%s\n' \
    "$status" "$rc" "$wall" "$budget" "$run_file" "$message" > "$dir/status.txt"
  echo "   $status (exit $rc) after $wall s"
done

fi  # report_only

# ---- 4. figures, maps and the report --------------------------------------------------------------
images="$root/docs/images/validation"
mkdir -p "$images"
# Only the pictures this script makes: other tools (e.g. tools/validation/plot_pareto.py) put theirs
# into the same folder.
for name in ritter stoker thacker lake_at_rest mangeney grid_block_pile particle_block particle_dambreak \
            particle_cut column_collapse; do
  rm -f "$images/$name.png"
done
rm -f "$images"/scene_*.png
"$py" tools/validation/plots.py "$out" "$images" || exit 1
"$py" tools/validation/report.py --template tools/validation/template.md --out docs/validation.md \
  --csv "$out" --scenes "$out/scenes" --images "$images" --parts docs/validation_parts \
  --gtest "$out/gtest.json,$out/gtest_column_collapse.json" --talus "$talus" --mode "$mode" --date "$(date -u '+%Y-%m-%d %H:%M UTC')" || exit 1
echo "== done in $(( $(date +%s) - t_start )) s: docs/validation.md, $(ls "$images"/*.png 2>/dev/null | wc -l) PNGs in docs/images/validation"

#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang-14 with ASan and UBSan) and runs each for SECONDS
# (default 60): fuzz_runfile (run-file text) and fuzz_raster (raster files through GDAL).
#   bash tools/fuzz.sh [SECONDS]
# The committed seed corpora (fuzz/corpus/runfile, fuzz/corpus/raster) are only read; new
# interesting inputs go to a scratch corpus, $TALUS_FUZZ_WORK/<target>/corpus (default
# build-fuzz/fuzz-work), which later runs start from. Crash, leak, timeout and out-of-memory inputs
# go to $TALUS_FUZZ_WORK/<target>/artifacts/. Exits non-zero when a target finds one, and prints the
# path of each such input; rerun one with: build-fuzz/fuzz/fuzz_<target> ARTIFACT
# Environment: TALUS_FUZZ_BUILD_DIR (default build-fuzz), TALUS_FUZZ_WORK, TALUS_FUZZ_JOBS (targets
# run at once, default: 2 when there are 2 or more cores, else 1).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
seconds=${1:-60}
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || (( seconds < 1 )); then
  echo "usage: bash tools/fuzz.sh [SECONDS]   (seconds per target, default 60)" >&2
  exit 1
fi
build_dir=${TALUS_FUZZ_BUILD_DIR:-build-fuzz}
[[ "$build_dir" = /* ]] || build_dir="$root/$build_dir"
work=${TALUS_FUZZ_WORK:-$build_dir/fuzz-work}
[[ "$work" = /* ]] || work="$root/$work"
targets=(runfile raster)
jobs=${TALUS_FUZZ_JOBS:-$(( $(nproc) >= 2 ? 2 : 1 ))}

for tool in clang-14 clang++-14; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "fuzz: $tool not found; run bash tools/setup.sh (installs clang-14 and libFuzzer)" >&2
    exit 1
  fi
done

start=$(date +%s)
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTALUS_BUILD_FUZZ=ON -DTALUS_BUILD_TESTS=OFF -DTALUS_BUILD_BENCH=OFF -DTALUS_BUILD_GUI=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target fuzz_runfile fuzz_raster fuzz_make_dict
echo "fuzz: built in $(( $(date +%s) - start )) s"

# The run-file dictionary, from the key registry of this build.
mkdir -p "$work"
dict="$work/runfile.dict"
"$build_dir/fuzz/fuzz_make_dict" >"$dict"
if ! cmp -s "$dict" fuzz/runfile.dict; then
  echo "fuzz: note: fuzz/runfile.dict differs from the keys of this build (regenerate it from $dict)"
fi

if [[ -z "${ASAN_SYMBOLIZER_PATH:-}" && -x /usr/lib/llvm-14/bin/llvm-symbolizer ]]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer  # function names and lines in reports
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:quarantine_size_mb=64}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# Runs one target for $seconds into its scratch corpus; its log goes to $work/<target>/fuzz.log.
run_target() {
  local name=$1
  local dir="$work/$name"
  local exe="$build_dir/fuzz/fuzz_$name"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  local extra=()
  [[ "$name" == runfile ]] && extra+=(-dict="$dict")
  # Known outside our code: libtiff allocates the strip size a corrupt TIFF declares (4.3 GB seen)
  # before failing; readRaster then reports it as InputError (tests/data/oom_huge_strip.tif.bin is
  # refused up front), but under ASan with a 2 GB limit libFuzzer counts such inputs as
  # out-of-memory. Longer hand runs may meet them; CI's fixed sequence below does not.
  # TALUS_FUZZ_SEED and TALUS_FUZZ_RUNS make a run reproducible (CI uses both: the same mutation
  # sequence, cut at the same length, whatever the machine's speed).
  [[ -n "${TALUS_FUZZ_SEED:-}" ]] && extra+=(-seed="$TALUS_FUZZ_SEED")
  [[ -n "${TALUS_FUZZ_RUNS:-}" ]] && extra+=(-runs="$TALUS_FUZZ_RUNS")
  local rc=0
  "$exe" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$dir/artifacts/" "${extra[@]}" "$dir/corpus" "fuzz/corpus/$name" \
    >"$dir/fuzz.log" 2>&1 || rc=$?
  return "$rc"
}

declare -A status pid
for name in "${targets[@]}"; do
  rm -rf "$work/$name/artifacts"
  mkdir -p "$work/$name/corpus" "$work/$name/artifacts"
  before=$(find "$work/$name/corpus" -type f | wc -l)
  echo "fuzz: $name: ${seconds} s from $(ls "fuzz/corpus/$name" | wc -l) seeds + $before scratch inputs"
done

for name in "${targets[@]}"; do
  if (( jobs > 1 )); then
    run_target "$name" &
    pid[$name]=$!
  else
    status[$name]=0
    run_target "$name" || status[$name]=$?
  fi
done
if (( jobs > 1 )); then
  for name in "${targets[@]}"; do
    status[$name]=0
    wait "${pid[$name]}" || status[$name]=$?
  done
fi

failed=0
for name in "${targets[@]}"; do
  dir="$work/$name"
  log="$dir/fuzz.log"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  size=$(find "$dir/corpus" -type f | wc -l)
  echo "fuzz: $name: exit ${status[$name]}, ${runs:-?} runs, ${speed:-?} exec/s, ${cov:-no coverage line}, scratch corpus $size inputs"
  mapfile -t found < <(find "$dir/artifacts" -type f | sort)
  if (( status[$name] != 0 || ${#found[@]} > 0 )); then
    failed=1
    echo "fuzz: $name: FAILED; from $log:" >&2
    grep -E '^==[0-9]+==ERROR|^SUMMARY: |^fuzz_(runfile|raster): |runtime error:' "$log" | head -8 >&2 || true
    echo "fuzz: $name: the end of $log:" >&2
    grep -vE '^"|# Uses:|^###### ' "$log" | tail -40 >&2
    for f in "${found[@]}"; do
      echo "fuzz: $name: crashing input: $f" >&2
    done
    (( ${#found[@]} > 0 )) || echo "fuzz: $name: no input was saved (see $log)" >&2
  fi
done

echo "fuzz: elapsed $(( $(date +%s) - start )) s"
if (( failed )); then
  echo "fuzz: FAILED (reproduce with: $build_dir/fuzz/fuzz_<target> <crashing input>)" >&2
  exit 1
fi
echo "fuzz: no crash"

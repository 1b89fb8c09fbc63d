#!/usr/bin/env bash
# Builds the test suite with AddressSanitizer and UndefinedBehaviorSanitizer (-DTALUS_SANITIZE=ON,
# the default compiler) in build-asan/ and runs the labels unit, kernels and verification there
# (without the longest physics runs; TALUS_SANITIZE_ALL=1 keeps them).
# Any sanitizer report fails the test it happens in (UBSan halts on the first error; LeakSanitizer
# stays on, with the OpenCL stack's own leaks suppressed by fuzz/lsan.supp).
#   bash tools/sanitize.sh [extra ctest arguments, e.g. -R Scene]
# Environment: TALUS_ASAN_BUILD_DIR (default build-asan), TALUS_TEST_JOBS (parallel ctest jobs,
# default 1), TALUS_DEVICE (device selection, passed through to the tests), TALUS_SANITIZE_ALL.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
build_dir=${TALUS_ASAN_BUILD_DIR:-build-asan}
[[ "$build_dir" = /* ]] || build_dir="$root/$build_dir"

if [[ -z "${ASAN_SYMBOLIZER_PATH:-}" && -x /usr/lib/llvm-14/bin/llvm-symbolizer ]]; then
  export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer  # function names and lines in reports
fi
# Set before the build too: test discovery runs the instrumented test executables.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/fuzz/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
if [[ -z "${XDG_CACHE_HOME:-}" && -z "${HOME:-}" ]]; then
  export XDG_CACHE_HOME="$build_dir/.cache"
fi
export POCL_KERNEL_CACHE="${POCL_KERNEL_CACHE:-1}"

start=$(date +%s)
# -O1 with line tables only (-g1): line numbers in the sanitizer reports at a fraction of the
# compile time of -O2 -g; NDEBUG as in the normal (Release) build.
# Without MPI: Open MPI's components are dlopen'ed and unloaded at MPI_Finalize, so LeakSanitizer
# reports their allocations under "<unknown module>", which no suppression can name. The ensemble
# code is still sanitized serially; its MPI test runs in the normal build (docs/ensembles.md).
cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DTALUS_SANITIZE=ON -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON \
  -DTALUS_BUILD_TESTS=ON -DTALUS_BUILD_BENCH=OFF -DTALUS_BUILD_GUI=OFF >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
built=$(date +%s)
echo "sanitize: built in $(( built - start )) s"

# The longest physics runs (over 20 s each in the normal build, 40-130 s instrumented) are left out
# here: they repeat for many thousand steps the host code (solver set-up, stepping, particle
# bookkeeping) that the shorter tests of the same solvers run under the sanitizers, and their
# kernels run in PoCL, which is not instrumented. They still run in the normal build (tools/test.sh).
# TALUS_SANITIZE_ALL=1 runs them too.
long_runs='ParticleColumnCollapse\.|ParticleBlock\.ElasticBar|ParticleBlock\.SlidesStressFreeOverFloatRoundOff'
long_runs+='|WellBalanced\.LakeAtRestAgainstLevelEdgesStaysAtRestForLong|RoughSlopeSheet\.FiveMetreMap'
long_runs+='|TerrainForcing\.FrictionlessMassClimbsBack|ParticleRealTerrain\.'
skip=(-E "$long_runs")
[[ "${TALUS_SANITIZE_ALL:-0}" == "1" ]] && skip=()

rc=0
ctest --test-dir "$build_dir" --output-on-failure --no-tests=error --timeout 1800 \
  -j "${TALUS_TEST_JOBS:-1}" -L 'unit|kernels|verification' "${skip[@]}" "$@" || rc=$?
echo "sanitize: tests took $(( $(date +%s) - built )) s"
if (( rc != 0 )); then
  echo "sanitize: FAILED (ctest exit status $rc; the failing tests and any sanitizer reports are above)" >&2
  exit "$rc"
fi
echo "sanitize: all tests passed under ASan and UBSan"

#!/usr/bin/env bash
# The engine's physics on a GPU machine that has CMake, a C++ compiler and its vendor's OpenCL
# driver but none of Talus's other packages (no GDAL, Qt or GoogleTest; no network), in well under
# 15 minutes (issue 16 item 4). Two steps:
#
#   bash tools/gpu_check.sh --prepare     here, once: copies what such a machine lacks into the
#                                         ignored folder .gpu_deps/ (GoogleTest's sources from
#                                         /usr/src/googletest, the OpenCL headers and the ICD
#                                         loader libOpenCL.so.1 of this Debian machine)
#   bash tools/gpu_check.sh [--quick]     there (e.g. the device tool's run with carry [".gpu_deps"]):
#                                         configures -DTALUS_PHYSICS_ONLY=ON into build-gpu/, builds
#                                         with every core, runs the kernel and verification tests and
#                                         bench_bandwidth, bench_flow and bench_particle_step on the
#                                         GPU's OpenCL device, and prints one table. --quick: the
#                                         kernel tests and the benchmarks only.
#
# The device: TALUS_DEVICE if set (an index, "cpu", or a substring of the device or platform name),
# else the first GPU. Where the machine's loader finds no ICD (containers often
# lack /etc/OpenCL/vendors), the driver's libnvidia-opencl.so.1 is named to the loader through
# OCL_ICD_FILENAMES. Logs go to $OUT (if set) or build-gpu/logs.
set -uo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deps="$root/.gpu_deps"

prepare() {
  rm -rf "$deps"
  mkdir -p "$deps/include" "$deps/lib"
  [[ -d /usr/src/googletest ]] || { echo "gpu_check: /usr/src/googletest missing (apt-get install googletest)" >&2; exit 1; }
  cp -r /usr/src/googletest "$deps/googletest"
  [[ -d /usr/include/CL ]] || { echo "gpu_check: /usr/include/CL missing (apt-get install opencl-headers)" >&2; exit 1; }
  cp -r /usr/include/CL "$deps/include/CL"
  local loader
  loader=$(ldconfig -p | awk '/libOpenCL\.so\.1 .*x86-64/ {print $NF; exit}')
  [[ -n "$loader" ]] || { echo "gpu_check: no libOpenCL.so.1 here (apt-get install ocl-icd-libopencl1)" >&2; exit 1; }
  cp -L "$loader" "$deps/lib/libOpenCL.so.1"
  ln -sf libOpenCL.so.1 "$deps/lib/libOpenCL.so"
  echo "gpu_check: prepared $(du -sh "$deps" | cut -f1) in .gpu_deps (carry it to the GPU machine)"
}

if [[ "${1:-}" == "--prepare" ]]; then
  prepare
  exit 0
fi
quick=0
[[ "${1:-}" == "--quick" ]] && quick=1

build="${GPU_CHECK_BUILD:-$root/build-gpu}"  # GPU_CHECK_BUILD: another build folder
logs="${OUT:-$build/logs}"
mkdir -p "$logs"
jobs=$(nproc)
start=$(date +%s)
say() { echo "gpu_check [$(( $(date +%s) - start )) s]: $*"; }

# OpenCL headers and loader: the machine's own (CUDA ships both), else the carried ones.
cmake_cl=()
if [[ ! -e /usr/include/CL/cl.h && ! -e /usr/local/cuda/include/CL/cl.h ]]; then
  [[ -d "$deps/include/CL" ]] || { say "no OpenCL headers and no .gpu_deps (run --prepare where they are)"; exit 1; }
  cmake_cl+=(-DOpenCL_INCLUDE_DIR="$deps/include")
elif [[ ! -e /usr/include/CL/cl.h ]]; then
  cmake_cl+=(-DOpenCL_INCLUDE_DIR=/usr/local/cuda/include)
fi
if ! ldconfig -p | grep -q 'libOpenCL\.so\.1 '; then
  if [[ -e /usr/local/cuda/lib64/libOpenCL.so.1 ]]; then
    cmake_cl+=(-DOpenCL_LIBRARY=/usr/local/cuda/lib64/libOpenCL.so.1)
    export LD_LIBRARY_PATH="/usr/local/cuda/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  else
    [[ -e "$deps/lib/libOpenCL.so.1" ]] || { say "no OpenCL loader and no .gpu_deps"; exit 1; }
    cmake_cl+=(-DOpenCL_LIBRARY="$deps/lib/libOpenCL.so.1")
    export LD_LIBRARY_PATH="$deps/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  fi
fi
# The vendor's ICD where no vendors file names it.
if [[ ! -d /etc/OpenCL/vendors || -z "$(ls /etc/OpenCL/vendors 2>/dev/null)" ]] && [[ -z "${OCL_ICD_FILENAMES:-}" ]]; then
  icd=$( (ldconfig -p | awk '/libnvidia-opencl\.so\.1/ {print $NF; exit}'; \
          ls /usr/local/nvidia/lib64/libnvidia-opencl.so.1 /usr/lib/x86_64-linux-gnu/libnvidia-opencl.so.1 2>/dev/null) | head -1)
  if [[ -n "$icd" ]]; then
    export OCL_ICD_FILENAMES="$icd"
    say "no ICD vendors file: OCL_ICD_FILENAMES=$icd"
  fi
fi
cmake_gtest=()
[[ -d "$deps/googletest" ]] && cmake_gtest+=(-DTALUS_GTEST_SOURCE="$deps/googletest")
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)

say "configuring (physics only) in build-gpu"
if ! cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DTALUS_PHYSICS_ONLY=ON \
     "${cmake_cl[@]}" "${cmake_gtest[@]}" >"$logs/configure.log" 2>&1; then
  tail -30 "$logs/configure.log"; say "configure FAILED"; exit 1
fi
say "building with $jobs jobs"
if ! cmake --build "$build" -j "$jobs" >"$logs/build.log" 2>&1; then
  grep -E "error|Error" "$logs/build.log" | head -30; say "build FAILED"; exit 1
fi

export TALUS_DEVICE="${TALUS_DEVICE:-gpu}"
export TALUS_CACHE_DIR="$build/kernel-cache"
labels='kernels|verification'
(( quick )) && labels='kernels'
say "tests ($labels) on device '$TALUS_DEVICE'"
ctest --test-dir "$build" -L "$labels" -j 4 --timeout 300 --output-on-failure >"$logs/tests.log" 2>&1
test_rc=$?
tests_line=$(grep -E "tests passed|tests failed" "$logs/tests.log" | tail -1)
failed=$(grep -E '\*\*\*Failed|\*\*\*Timeout|Exception' "$logs/tests.log" | sed 's/^ *//' | head -20)

say "benchmarks"
bin="$build/bench"
"$bin/bench_bandwidth" --mib 1024 --precision float,double --device "$TALUS_DEVICE" >"$logs/bench_bandwidth.log" 2>&1
"$bin/bench_flow" --sizes 1000,4000 --precision float,double --device "$TALUS_DEVICE" >"$logs/bench_flow.log" 2>&1
"$bin/bench_particle_step" --sizes 100000,1000000 --precision float --device "$TALUS_DEVICE" >"$logs/bench_particle_step.log" 2>&1

echo
echo "=== gpu_check: $(grep -m1 "^device:" "$logs/bench_bandwidth.log" || echo "device $TALUS_DEVICE (no bench_bandwidth output)")"
echo "tests ($labels): ${tests_line:-no summary (see tests.log)}"
[[ -n "$failed" ]] && echo "$failed"
for b in bench_bandwidth bench_flow bench_particle_step; do
  echo "--- $b"
  # the benchmarks' own summary lines (figures per size and precision)
  grep -E "GB/s|updates/s|not run|speed-up|bench_" "$logs/$b.log" | head -24
done
say "done (tests exit $test_rc); logs in $logs"
exit $test_rc

#!/usr/bin/env bash
# Compiles every OpenCL kernel file (kernels/*/*.cl) with clang's OpenCL front end under each
# variant of the compile-time switches the engine uses (precision, limiter, Riemann solver and the
# optional physics: viscous, particle bed, curvature; each basal law; the split time scheme with
# its draining-time limiter) and fails on any warning. A device compiler
# that prints only "N warnings generated." (PoCL) then never hides one, and a warning that only a
# rarely used variant shows is found here rather than by a user.
# Needs clang (clang-14 in CI, installed by tools/setup.sh for the fuzz targets); skips with a
# message when there is none.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
clang=""
for c in clang-14 clang; do
  if command -v "$c" >/dev/null 2>&1; then clang=$c; break; fi
done
if [[ -z "$clang" ]]; then
  echo "check_kernels: no clang found; kernel warnings not checked" >&2
  exit 0
fi

failed=0
count=0
for file in "$root"/kernels/*/*.cl; do
  for precision in 0 1; do
    for limiter in 0 1 2 3; do
      for optional in 0 1; do
        defines=(-DTALUS_DOUBLE=$precision -DLIMITER=$limiter -DRIEMANN=$(( limiter % 2 )) -DTILE=16
                 -DDEBRIS_VISCOUS=$optional -DDEBRIS_OBSTACLE=$optional -DDEBRIS_CURVATURE=$optional
                 -DPARTICLE_CURVATURE=$optional -DPARTICLE_METRIC=$optional -DMANNING_ALONG_BED=$optional -DRHEOLOGY=$limiter -DSPLIT=$optional
                 -DHANCOCK=$(( optional && limiter % 2 )))
        count=$(( count + 1 ))
        if ! out=$("$clang" -x cl -cl-std=CL1.2 -fsyntax-only -Xclang -finclude-default-header -Werror \
                   "${defines[@]}" -I"$root/kernels" "$file" 2>&1); then
          echo "check_kernels: ${file#$root/} (${defines[*]}):" >&2
          echo "$out" | head -20 >&2
          failed=1
        fi
      done
    done
  done
done
if (( failed )); then
  echo "check_kernels: FAILED" >&2
  exit 1
fi
echo "check_kernels: $count kernel builds without warnings"

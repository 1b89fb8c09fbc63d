#!/usr/bin/env bash
# Times an ensemble serially and over N MPI ranks and prints members per hour and the parallel
# efficiency (docs/ensembles.md, "Benchmark"). Usage: bash tools/bench_ensemble.sh [ENSEMBLE] [N]
# (default: data/kot_dambreak/kot_ensemble.ens, N = 2). Writes into a temporary folder.
# END_TIME=MIN shortens every member's run (a one-value design parameter "End Time=list MIN");
# REPS=K repeats the serial/MPI pair K times, interleaved, so that a drifting machine load affects
# both alike; every repetition is printed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
talus=${TALUS_BINARY:-$root/build/src/talus}
ens=$(realpath "${1:-$root/data/kot_dambreak/kot_ensemble.ens}")
ranks=${2:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Copies of the ensemble file with their own output folder and an absolute run-file path.
runfile=$(sed -n 's/^ *Run File *= *//p' "$ens")
[[ "$runfile" = /* ]] || runfile="$(dirname "$ens")/$runfile"
members=$(sed -n 's/^ *Members *= *//p' "$ens")
reps=${REPS:-1}
for rep in $(seq "$reps"); do
  for name in serial mpi; do
    sed -e "s|^ *Run File *=.*|Run File=$runfile|" -e "s|^ *Output Directory *=.*|Output Directory=$work/$name$rep|" \
      "$ens" > "$work/$name$rep.ens"
    if [[ -n "${END_TIME:-}" ]]; then sed -i "s|^\[Parameters\]|[Parameters]\nEnd Time=list $END_TIME|" "$work/$name$rep.ens"; fi
  done
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Warm the kernel cache so that neither timing includes the first kernel build.
"$talus" run "$runfile" --out "$work/warm" --quiet --set "End Time=0.001" >/dev/null
for rep in $(seq "$reps"); do
  t0=$(date +%s.%N); "$talus" ensemble "$work/serial$rep.ens" --quiet; t1=$(date +%s.%N)
  mpirun -np "$ranks" --oversubscribe "$talus" ensemble "$work/mpi$rep.ens" --quiet; t2=$(date +%s.%N)
  cmp_all=identical
  for f in "$work/serial$rep"/merged/*; do
    cmp -s "$f" "$work/mpi$rep/merged/$(basename "$f")" || cmp_all="DIFFERENT ($(basename "$f"))"
  done
  awk -v s="$(echo "$t1 - $t0" | bc)" -v p="$(echo "$t2 - $t1" | bc)" -v n="$members" -v r="$ranks" -v c="$cmp_all" \
    -v load="$(cut -d' ' -f1-3 /proc/loadavg)" 'BEGIN {
    printf "members %d, serial %.2f s (%.0f members/hour), %d ranks %.2f s (%.0f members/hour); ", n, s, 3600 * n / s, r, p, 3600 * n / p
    printf "speed-up %.2f, parallel efficiency %.0f %%, merged maps %s; load average %s\n", s / p, 100 * s / (p * r), c, load }'
done

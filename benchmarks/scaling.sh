#!/usr/bin/env bash
# Usage: benchmarks/scaling.sh [RBC_IFEM] [RANKS] [CELLS...]
#
# How a flowing run's step grows with the number of cells (issue 51's
# yardstick): N uniform cells, one per 5 µm of a periodic capillary of
# 5N µm (the prm/default.prm cell and meshes, semi-implicit at its step, no
# DM), for each N of CELLS (default 4 16 64) on RANKS ranks (default 2).
# Each N runs 1 step and 3 steps:
#  - seconds per step, and per cell: in the 3-step run, the wall time from
#    the end of step 1 to the end of step 3 over 2 (the progress lines), so
#    that the machine's noise between two runs does not enter;
#  - collective MPI calls and point-to-point bytes sent per step, the
#    largest over the ranks, the difference of the two runs over 2, counted by benchmarks/mpi_counts.c (built here
#    with mpicc and preloaded; it changes nothing the calls do);
#  - the peak memory of the largest rank in the 3-step run (the program's
#    report).
# The rows go to doc/results/benchmarks/scaling.csv (benchmarks/common.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
here=$(cd "$(dirname "$0")" && pwd)
benchmark_setup "${1:-}" "${2:-2}"
shift $(($# < 2 ? $# : 2))
cells=("${@:-4 16 64}")
read -r -a cells <<<"${cells[*]}"

mpicc -shared -fPIC -O2 -o libmpi_counts.so "$here/mpi_counts.c"

# run N STEPS: the run of N cells for STEPS steps into run_N_STEPS/, its
# counts in counts_N_STEPS.RANK
run() {
  mpirun --oversubscribe -np "$ranks" -x LD_PRELOAD="$PWD/libmpi_counts.so" \
    -x RBC_MPI_COUNTS="$PWD/counts_$1_$2" \
    "$exe" "$(dirname "$here")/prm/default.prm" \
    --set "Output directory=run_$1_$2" --set "Time/Number of steps=$2" \
    --set "Immersed cells/Diffusion interval=0" \
    --set "Geometry/Periodic=true" --set "Geometry/Capillary length=$((5 * $1))" \
    --set "Layout/Number of cells=$1" >"log_$1_$2.txt"
}
# wall_after N STEP: the wall time at the end of step STEP of the 3-step run
# of N cells [s] (its progress line: "[wall 12.3 s" or "[wall 1 min 05 s")
wall_after() {
  sed -n "s/^  step $2 of 3,.*\[wall \([^,]*\),.*/\1/p" "log_$1_3.txt" |
    awk '{print ($2 == "min") ? 60 * $1 + $3 : $1}'
}
# per_step N COLUMN: the largest over the ranks of (3-step - 1-step) / 2 of
# that column of the counts (2 collectives, 4 bytes)
per_step() {
  paste -d' ' <(sort -n counts_"$1"_1.* | awk '{print $1, $'"$2"'}') \
    <(sort -n counts_"$1"_3.* | awk '{print $'"$2"'}') |
    awk '{d = ($3 - $2) / 2; if (d > m) m = d} END {printf "%.0f", m}'
}

results_table scaling ranks cells "fluid DoFs" "step [s]" "step per cell [s]" \
  "collectives per step" "bytes sent per step" "peak memory per rank [MB]"
for n in "${cells[@]}"; do
  run "$n" 1
  run "$n" 3
  dofs=$(sed -n 's/.*fluid mesh: [0-9]* cells, \([0-9]*\) DoFs.*/\1/p' "log_${n}_3.txt")
  step=$(awk -v a="$(wall_after "$n" 1)" -v b="$(wall_after "$n" 3)" 'BEGIN {printf "%.2f", (b - a) / 2}')
  per_cell=$(awk -v s="$step" -v n="$n" 'BEGIN {printf "%.3f", s / n}')
  memory=$(sed -n 's/.*peak memory: \([0-9.]*\) MB.*/\1/p' "log_${n}_3.txt")
  results_row "$ranks" "$n" "$dofs" "$step" "$per_cell" "$(per_step "$n" 2)" \
    "$(per_step "$n" 4)" "$memory"
done

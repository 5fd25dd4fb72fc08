#!/usr/bin/env bash
# Usage: benchmarks/scaling.sh [RBC_IFEM] [RANKS] [CELLS...]
#
# How a flowing run's step grows with the number of cells (issue 51's
# yardstick): N uniform cells, one per 5 µm of a periodic capillary of
# 5N µm (the prm/default.prm cell and meshes, semi-implicit at its step, no
# DM), for each N of CELLS (default 4 16 64) on RANKS ranks (default 2).
# N = 0 is the empty run: prm/default.prm's 20 µm capillary without cells,
# the fixed cost every rank pays whatever the cells (the program, MPI and a
# small mesh); its columns but the memory stay empty or count the fluid's
# steps only.
# Each N runs 3 steps:
#  - seconds per step, and per cell: the wall time from the end of step 1
#    to the end of step 3 over 2 (the progress lines), so that the set-up
#    and the first step's one-off work do not enter;
#  - collective MPI calls, point-to-point bytes sent and the bytes put into
#    the collective calls per step, the mean over the 3 steps of the largest
#    rank, as the program counts them (MpiTraffic, its line "per rank and
#    step, least to most");
#  - the peak memory of the largest rank (the program's report).
# The rows go to doc/results/benchmarks/scaling.csv (benchmarks/common.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
here=$(cd "$(dirname "$0")" && pwd)
benchmark_setup "${1:-}" "${2:-2}"
shift $(($# < 2 ? $# : 2))
cells=("${@:-4 16 64}")
read -r -a cells <<<"${cells[*]}"

# run N: the run of N cells for 3 steps into run_N/, its log log_N.txt
run() {
  local cells=(--set "Immersed cells/Enabled=false")
  if [ "$1" -gt 0 ]; then
    # The membranes grouped: a piece per rank, not a file per cell.
    cells=(--set "Geometry/Capillary length=$((5 * $1))" --set "Layout/Number of cells=$1"
      --set "Immersed cells/Membrane files=grouped")
  fi
  mpirun --oversubscribe -np "$ranks" "$exe" "$(dirname "$here")/prm/default.prm" \
    --set "Output directory=run_$1" --set "Time/Number of steps=3" \
    --set "Immersed cells/Diffusion interval=0" --set "Geometry/Periodic=true" \
    "${cells[@]}" >"log_$1.txt"
}
results_table scaling ranks cells "fluid DoFs" "step [s]" "step per cell [s]" \
  "collectives per step" "bytes sent per step" "peak memory per rank [MB]" \
  "bytes into collectives per step"
for n in "${cells[@]}"; do
  run "$n"
  dofs=$(sed -n -e 's/.*fluid mesh: [0-9]* cells, \([0-9]*\) DoFs.*/\1/p' \
    -e 's/^  mesh: [0-9]* cells; \([0-9]*\) DoFs.*/\1/p' "log_${n}.txt")
  step=$(step_seconds "log_$n.txt")
  per_cell=$(awk -v s="$step" -v n="$n" 'BEGIN {if (n > 0) printf "%.3f", s / n}')
  memory=$(peak_memory "log_${n}.txt")
  results_row "$ranks" "$n" "$dofs" "$step" "$per_cell" \
    "$(per_step "log_$n.txt" "collective MPI calls")" "$(per_step "log_$n.txt" "bytes sent")" "$memory" \
    "$(per_step "log_$n.txt" "bytes into collectives")"
done

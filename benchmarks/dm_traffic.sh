#!/usr/bin/env bash
# Usage: benchmarks/dm_traffic.sh BEFORE AFTER [RANKS] [CELLS...]
#
# Whether a flowing run's steps with a DM solve in them still ask of MPI a
# number of collective calls that does not grow with the cells (issue 51's
# target "collectives per step independent of N"; doc/scaling.md Section
# 15): two rbc-ifem programs, BEFORE and AFTER a change, one after the other
# in this script, each on N uniform cells, one per 5 µm of a periodic
# capillary of 5N µm, for each N of CELLS (default 16 64), the
# prm/default.prm cell and meshes, 3 steps with a DM solve at the third
# (Immersed cells/Diffusion interval = 3), on RANKS ranks (default 2). Per
# program and N: the collective calls and the bytes put into them per step
# (the mean over the 3 steps of the largest rank, as the program counts
# them, MpiTraffic), and the DM at the end (dm.csv), which the two programs
# must give alike. The rows go to doc/results/benchmarks/dm_traffic.csv.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
before_after_setup "$@"
shift $(($# < 3 ? $# : 3))
cells=("${@:-16 64}")
read -r -a cells <<<"${cells[*]}"

# run NAME PROGRAM N: N cells for 3 steps into NAME_N/, the log NAME_N.log
run() {
  mpirun --oversubscribe -np "$ranks" "$2" "$here/prm/default.prm" \
    --set "Output directory=$1_$3" --set "Time/Number of steps=3" \
    --set "Immersed cells/Diffusion interval=3" --set "Geometry/Periodic=true" \
    --set "Geometry/Capillary length=$((5 * $3))" --set "Layout/Number of cells=$3" \
    --set "Immersed cells/Membrane files=grouped" >"$1_$3.log"
}

# last_dm DIR: the last DM of DIR/dm.csv, as written
last_dm() { tail -n 1 "$1/dm.csv" | cut -d, -f2; }

results_table dm_traffic ranks cells program "collectives per step" \
  "bytes into collectives per step" "last DM"
for n in "${cells[@]}"; do
  for name in before after; do
    run "$name" "${!name}" "$n"
    results_row "$ranks" "$n" "$name" \
      "$(per_step "${name}_$n.log" "collective MPI calls")" \
      "$(per_step "${name}_$n.log" "bytes into collectives")" \
      "$(last_dm "${name}_$n")"
  done
done

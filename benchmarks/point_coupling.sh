#!/usr/bin/env bash
# Usage: benchmarks/point_coupling.sh BEFORE AFTER [RANKS] [CELLS]
#
# What the semi-implicit coupling sends when its load goes point to point
# (issue 51, item 2; doc/scaling.md Section 10): two rbc-ifem programs,
# BEFORE and AFTER a change, run side by side, one after the other in this
# script, on benchmarks/scaling.sh's case: CELLS uniform cells (default 64),
# one per 5 µm of a periodic capillary, the prm/default.prm cell and meshes,
# semi-implicit at its step, membranes grouped, 3 steps, no DM, on RANKS
# ranks (default 2). Per program: seconds per step (from the end of step 1
# to the end of step 3), rank 0's seconds per step in the load L v inside
# the FGMRES iterations and V-cycles ("coupling: implicit force load"), the
# largest rank's collective calls and point-to-point bytes per step, and
# how far AFTER's cells.csv is from BEFORE's (benchmarks/common.sh,
# cells_difference). The rows go to
# doc/results/benchmarks/point_coupling.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
before_after_setup "$@"

run() {
  mpirun --oversubscribe -np "$ranks" "$2" "$here/prm/default.prm" \
    --set "Output directory=$1" --set "Time/Number of steps=3" \
    --set "Immersed cells/Diffusion interval=0" --set "Geometry/Periodic=true" \
    --set "Geometry/Capillary length=$((5 * cells))" \
    --set "Layout/Number of cells=$cells" \
    --set "Immersed cells/Membrane files=grouped" >"$1.log"
}
run before "$before"
run after "$after"

difference=$(cells_difference before after)

results_table point_coupling ranks cells program "step [s]" \
  "load L v [s per step]" "collectives per step" "bytes sent per step" \
  "cells.csv difference"
for name in before after; do
  step=$(step_seconds $name.log)
  load=$(awk -v t="$(section_seconds $name "coupling: implicit force load")" \
    'BEGIN {printf "%.2f", t / 3}')
  results_row "$ranks" "$cells" "$name" "$step" "$load" \
    "$(per_step $name.log "collective MPI calls")" "$(per_step $name.log "bytes sent")" \
    "$([ $name = after ] && echo "$difference")"
done

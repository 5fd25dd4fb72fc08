#!/usr/bin/env bash
# Usage: benchmarks/clustered_balance.sh BEFORE AFTER [RANKS] [CELLS]
#
# How evenly the ranks share the fluid mesh of a clustered layout (issue
# 51, item 4; doc/scaling.md Section 13): two rbc-ifem programs, BEFORE and
# AFTER a change, run side by side, one after the other in this script.
# The case: CELLS cells (default 8) stacked at the layout's minimum gap,
# the group centred at 0.3 of a periodic capillary of 10 µm per cell, the
# prm/default.prm cell and meshes (the fluid mesh refined once more within
# 1 µm of the cells), 3 steps, no DM, on RANKS ranks (default 2). Per
# program: the least and most fluid cells and membrane points of a rank
# (the program's load-balance line), seconds per step (from the end of step
# 1 to the end of step 3), the peak memory of the largest rank, and how far
# AFTER's cells.csv is from BEFORE's (benchmarks/common.sh,
# cells_difference). The rows go to doc/results/benchmarks/clustered_balance.csv.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
default_cells=8 before_after_setup "$@"

run() {
  mpirun --oversubscribe -np "$ranks" "$2" "$here/prm/default.prm" \
    --set "Output directory=$1" --set "Time/Number of steps=3" \
    --set "Immersed cells/Diffusion interval=0" --set "Geometry/Periodic=true" \
    --set "Geometry/Capillary length=$((10 * cells))" \
    --set "Layout/Kind=clustered" --set "Layout/Cluster position=0.3" \
    --set "Layout/Number of cells=$cells" >"$1.log"
}
run before "$before"
run after "$after"
difference=$(cells_difference before after)

results_table clustered_balance ranks cells program "fluid cells per rank" \
  "membrane points per rank" "step [s]" "peak memory per rank [MB]" \
  "cells.csv difference"
for name in before after; do
  results_row "$ranks" "$cells" "$name" "$(load_balance $name.log "fluid cells")" \
    "$(load_balance $name.log "membrane points")" "$(step_seconds $name.log)" \
    "$(peak_memory $name.log)" \
    "$([ $name = after ] && echo "$difference")"
done

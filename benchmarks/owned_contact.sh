#!/usr/bin/env bash
# Usage: benchmarks/owned_contact.sh BEFORE AFTER [RANKS] [CELLS]
#
# What each rank spends on contact when its cells' contact is its own
# (issue 51, item 3): two rbc-ifem programs, BEFORE and AFTER a change,
# run side by side, one after the other in this script, on the same case:
# CELLS uniform cells (default 64) touching each other, one per 2.7 µm of a
# periodic capillary (0.24 µm gaps, inside the 0.3 µm repulsion range, the
# last cell touching the first across the end), the prm/default.prm cell
# and meshes, semi-implicit at Δt = 3e-5 s (the automatic step's FGMRES
# stalls at such gaps: doc/scaling.md), 2 steps, no DM, on RANKS ranks
# (default 2). Per program, from rank 0's timing.csv, per step: the forces
# (membrane elasticity plus contact, wall and their reduction), the tangent
# stiffness (likewise) and the gap check. The rows go to
# doc/results/benchmarks/owned_contact.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
before_after_setup "$@"
length=$(awk -v n="$cells" 'BEGIN {print 2.7 * n}')

run() {
  mpirun --oversubscribe -np "$ranks" "$2" "$here/prm/default.prm" \
    --set "Output directory=$1" --set "Time/Number of steps=2" \
    --set "Time/Time step=3e-5" --set "Time/Output interval=2" \
    --set "Immersed cells/Diffusion interval=0" \
    --set "Immersed cells/Checkpoint interval=0" \
    --set "Geometry/Periodic=true" --set "Geometry/Capillary length=$length" \
    --set "Layout/Number of cells=$cells" --set "Layout/Minimum gap=0.2" >"$1.log"
}
run before "$before"
run after "$after"

results_table owned_contact ranks cells program "s per step" \
  "forces [s per step]" "stiffness [s per step]" "gap check [s per step]" \
  "smallest gap [µm]"
for name in before after; do
  per_step=$(sed -n 's/.* steps in .* s, \(.*\) s per step/\1/p' $name.log)
  gap=$(sed -n 's/.*smallest gap between cells \([0-9.e-]*\) µm.*/\1/p' $name.log | tail -1)
  results_row "$ranks" "$cells" "$name" "$(printf '%.2f' "$per_step")" \
    "$(awk -v t="$(section_seconds $name "membrane forces")" 'BEGIN {printf "%.3f", t / 2}')" \
    "$(awk -v t="$(section_seconds $name "membrane stiffness")" 'BEGIN {printf "%.3f", t / 2}')" \
    "$(awk -v t="$(section_seconds $name "contact check")" 'BEGIN {printf "%.3f", t / 2}')" \
    "$gap"
done

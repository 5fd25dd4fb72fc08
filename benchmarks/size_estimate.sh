#!/usr/bin/env bash
# Usage: benchmarks/size_estimate.sh [RBC_IFEM] [RANKS]
#
# The size estimate a flowing run prints before it builds a mesh
# (SizeEstimate, include/rbc_ifem/ifem/size_estimate.h) against what the
# run then builds and uses: prm/default.prm for two steps of 2e-5 s (one DM
# solve at the start, one at step 2) at fluid global refinements 1, 2 and 3
# and diffusion band refinements 1 and 2, with 1 cell, and with 7. For each: the estimated and the
# built fluid cells and DoFs, the estimated memory per rank and the peak
# the run reports, and their ratio. Prints a Markdown table and adds its
# rows to doc/results/benchmarks/size_estimate.csv (benchmarks/common.sh).
# RBC_IFEM defaults to build/rbc-ifem, RANKS to 1. About 3 minutes.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "${1:-}" "${2:-}"

results_table size_estimate ranks "fluid refinements" "diffusion band refinements" cells "fluid cells: estimate" \
  "fluid cells: built" "fluid DoFs: estimate" "fluid DoFs: built" "diffusion DoFs: estimate" "memory per rank: estimate [MB]" \
  "peak [MB]" "estimate / peak"
for run in "1 1 1" "2 1 1" "3 1 1" "1 2 1" "1 1 7"; do
  read -r fluid band n <<<"$run"
  rm -rf out
  mpirun -np "$ranks" "$exe" "$here/prm/default.prm" --set "Output directory=out" \
    --set "Mesh/Fluid global refinements=$fluid" --set "Mesh/Diffusion band refinements=$band" \
    --set "Layout/Number of cells=$n" \
    --set "Time/Number of steps=2" --set "Time/Time step=2e-5" --set "Immersed cells/Diffusion interval=2" \
    --set "Immersed cells/Checkpoint interval=0" --set "Time/Output interval=1000" >log.txt 2>&1 ||
    { tail -5 log.txt; exit 1; }
  read -r est_cells est_dofs est_diffusion est_mb < <(sed -n \
    's/.*size estimate: fluid mesh about \([^ ]*\) cells, \([^ ]*\) DoFs; diffusion mesh about [^ ]* cells, \([^ ]*\) DoFs; [^;]*; about \([^ ]*\) MB per rank.*/\1 \2 \3 \4/p' log.txt)
  read -r cells dofs < <(sed -n 's/^  fluid mesh: \([0-9]*\) cells, \([0-9]*\) DoFs.*/\1 \2/p' log.txt)
  peak=$(sed -n 's/^  peak memory: \([0-9.]*\) MB.*/\1/p' log.txt)
  results_row "$ranks" "$fluid" "$band" "$n" "$est_cells" "$cells" "$est_dofs" "$dofs" "$est_diffusion" "$est_mb" \
    "$peak" "$(awk -v a="$est_mb" -v b="$peak" 'BEGIN { printf "%.2f", a / b }')"
done

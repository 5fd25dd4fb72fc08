#!/usr/bin/env bash
# Usage: benchmarks/membrane_files.sh [RBC_IFEM] [RANKS] [CELLS]
#
# The membranes written per cell against grouped (Immersed cells/Membrane
# files), side by side in one script run: CELLS uniform cells (default 64),
# one per 5 µm of a periodic capillary of 5 CELLS µm (prm/default.prm's
# cell and meshes, no DM), on RANKS ranks (default 2), 2 steps with an
# output at every step (3 outputs). For each kind: the files the membranes
# write per output (its VTU or PVTU files, and every .pvd rewritten), their megabytes per output, and the
# TimerOutput section "output" per output (rank 0's wall time, the fluid's
# pieces included, which both kinds write alike).
# The rows go to doc/results/benchmarks/membrane_files.csv.
set -euo pipefail
source "$(dirname "$0")/common.sh"
here=$(cd "$(dirname "$0")" && pwd)
benchmark_setup "${1:-}" "${2:-2}"
cells=${3:-64}

# membranes FIND_TESTS...: the membranes' files in $out that pass them.
membranes() { find "$out" -maxdepth 1 \( -name 'cell_*' -o -name 'membranes*' \) "$@"; }

results_table membrane_files ranks cells "membrane files" "files per output" \
  "MB per output" "output per output [s]"
for kind in "per cell" grouped; do
  out=run_${kind// /_}
  mpirun --oversubscribe -np "$ranks" "$exe" "$(dirname "$here")/prm/default.prm" \
    --set "Output directory=$out" --set "Time/Number of steps=2" \
    --set "Time/Output interval=1" --set "Immersed cells/Diffusion interval=0" \
    --set "Immersed cells/Checkpoint interval=0" --set "Geometry/Periodic=true" \
    --set "Geometry/Capillary length=$((5 * cells))" --set "Layout/Number of cells=$cells" \
    --set "Immersed cells/Membrane files=$kind" >"$out.log"
  # Each output writes its VTU or PVTU files and rewrites every .pvd.
  pieces=$(membranes -name '*vtu' | wc -l)
  series=$(membranes -name '*.pvd' | wc -l)
  bytes=$(membranes -name '*vtu' -printf '%s\n' | awk '{ s += $1 } END { print s }')
  seconds=$(section_seconds "$out" output)
  results_row "$ranks" "$cells" "$kind" "$((pieces / 3 + series))" \
    "$(awk -v b="$bytes" 'BEGIN { printf "%.1f", b / 3 / 1048576 }')" \
    "$(awk -v t="$seconds" 'BEGIN { printf "%.2f", t / 3 }')"
done

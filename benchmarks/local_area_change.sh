#!/bin/bash
# The largest local area change of the default parachute at the stretching
# experiment's area dilation modulus K = 500 pN/µm, on the default membrane
# and on one refined once more, in one run of this script:
#
#   bash benchmarks/local_area_change.sh [path/to/rbc-ifem] [ranks, default 2]
#
# - Surface refinements 4 (prm/default.prm, 1536 membrane cells) and 5
#   (6144 cells, with Mesh/Fluid band refinements 2 to keep the membrane
#   points' spacing to the fluid mesh size as it is);
# - semi-implicit at Δt = 4e-5 s, 300 steps (12 ms), no DM solves.
#
# Prints, at every 1.2 ms, cells.csv's local_area_change (max over the
# membrane cells of |A/A0 - 1|) and the deformation index of both runs, and
# each run's wall time, and adds them to
# doc/results/benchmarks/local_area_change.csv and
# local_area_change_wall.csv (benchmarks/common.sh). About 6 minutes on 2
# ranks.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
benchmark_setup "${1:-}" "${2:-2}"

# run NAME SURFACE_REFINEMENTS FLUID_BAND_REFINEMENTS
run() {
  { cat "$here/prm/default.prm"
    cat <<PRM
set Output directory = $1
subsection Cells
  set Surface refinements = $2
end
subsection Mesh
  set Fluid band refinements = $3
end
subsection Membrane
  set Area dilation modulus = 500
end
subsection Time
  set Time step       = 4e-5
  set Number of steps = 300
  set Output interval = 30
end
subsection Immersed cells
  set Diffusion interval        = 0
  set Checkpoint interval       = 0
  set Maximum step displacement = 1
end
PRM
  } > "$1.prm"
  local start
  start=$(date +%s.%N)
  mpirun -np "$ranks" "$exe" "$1.prm" > "$1.log"
  echo "$(date +%s.%N) - $start" | bc > "$1.seconds"
}

run surface4 4 1
run surface5 5 2

# column RUN NAME: the column NAME of RUN's cells.csv, without its header.
column() { awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } { print $c }' "$1/cells.csv"; }
echo "## K = 500 pN/µm, semi-implicit at 4e-5 s: the largest local area change"
echo
results_table local_area_change ranks "t [ms]" "1536 membrane cells" "6144 membrane cells" \
  "deformation index, 1536" "deformation index, 6144"
paste -d, <(column surface4 time) <(column surface4 local_area_change) <(column surface5 local_area_change) \
  <(column surface4 deformation_index) <(column surface5 deformation_index) |
  awk -F, '{ printf "%.1f %.3f%% %.3f%% %.6f %.6f\n", 1000 * $1, 100 * $2, 100 * $3, $4, $5 }' |
  while read -r -a row; do results_row "$ranks" "${row[@]}"; done
echo
results_table local_area_change_wall ranks "membrane cells" "wall [s]"
results_row "$ranks" 1536 "$(printf '%.1f' "$(cat surface4.seconds)")"
results_row "$ranks" 6144 "$(printf '%.1f' "$(cat surface5.seconds)")"

#!/usr/bin/env bash
# Usage: benchmarks/geometry.sh [RBC_IFEM] [RANKS]
#
# Times the geometry experiment (seven uniform cells, the paper's full
# capillary) at increasing mesh sizes: fluid and diffusion mesh cells, the
# wall seconds of each TimerOutput section, and the peak memory. Prints a
# Markdown table and adds its rows to doc/results/benchmarks/geometry.csv
# (benchmarks/common.sh). RBC_IFEM defaults to build/rbc-ifem, RANKS to 1.
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

results_table geometry ranks "global refinements" "surface refinements" "fluid cells" "diffusion cells" \
  "membranes [s]" "clearance [s]" "fluid mesh [s]" "diffusion mesh [s]" "output [s]" "peak memory [MB]"
for level in 1 2 3; do
  surface=$((level + 2))
  cat > run.prm <<PRM
set Output directory = out
subsection Mesh
  set Fluid global refinements     = $level
  set Diffusion global refinements = $level
end
subsection Cells
  set Surface refinements = $surface
end
subsection Layout
  set Number of cells = 7
end
PRM
  mpirun -np "$ranks" "$exe" run.prm > log.txt
  read -r fluid_cells diffusion_cells <<<"$(sed -n 's/.*fluid mesh: \([0-9]*\) cells, diffusion mesh: \([0-9]*\) cells.*/\1 \2/p' log.txt)"
  memory=$(peak_memory log.txt)
  seconds() { awk -F, -v s="\"$1\"" '$1 == s {printf "%.2f", $3}' out/timing.csv; }
  results_row "$ranks" "$level" "$surface" "$fluid_cells" "$diffusion_cells" "$(seconds membranes)" \
    "$(seconds "clearance check")" "$(seconds "fluid mesh")" "$(seconds "diffusion mesh")" "$(seconds output)" "${memory%.*}"
done

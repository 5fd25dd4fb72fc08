#!/usr/bin/env bash
# Usage: benchmarks/membrane.sh [RBC_IFEM]
#
# The membrane mechanics at the sizes the experiments use: the stretching
# experiment (Skalak, 0 to 200 pN in 8 steps, 1e-3 pN) for Q1 membranes
# on Evans-Fung meshes of 2, 3 and 4 surface refinements, and a Q2 membrane
# with as many DoFs as the Q1 one of 3 refinements. Per run: cells, DoFs, L-BFGS iterations in all, seconds per
# iteration (one energy-and-force evaluation and its line search), the
# axial diameter at 200 pN, and the total time. Prints a Markdown table and
# adds its rows to doc/results/benchmarks/membrane.csv (benchmarks/common.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

results_table membrane degree refinements cells DoFs "L-BFGS iterations" "ms per iteration" \
  "axial diameter at 200 pN [µm]" "total [s]"
for run in "1 2" "1 3" "1 4" "2 2"; do
  read -r degree level <<<"$run"
  cat > run.prm <<PRM
set Experiment = stretching
set Output directory = out
subsection Cells
  set Surface refinements = $level
end
subsection Membrane
  set Elastic law           = Skalak
  set Finite element degree = $degree
end
PRM
  start=$(date +%s.%N)
  "$exe" run.prm > log.txt
  total=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}')
  read -r cells dofs <<<"$(sed -n 's/.*membrane: \([0-9]*\) cells, \([0-9]*\) DoFs.*/\1 \2/p' log.txt)"
  iterations=$(awk -F, 'NR > 1 {n += $6} END {print n}' out/stretch.csv)
  per_iteration=$(awk -F, -v n="$iterations" '$1 == "\"equilibrium\"" {printf "%.1f", 1000 * $3 / n}' out/timing.csv)
  axial=$(awk -F, 'END {printf "%.3f", $2}' out/stretch.csv)
  results_row "$degree" "$level" "$cells" "$dofs" "$iterations" "$per_iteration" "$axial" "$(printf '%.0f' "$total")"
done

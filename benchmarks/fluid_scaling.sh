#!/usr/bin/env bash
# Usage: benchmarks/fluid_scaling.sh [RBC_IFEM]
#
# The plasma's Stokes step at about a million DoFs (a 40 µm capillary,
# Mesh/Fluid global refinements = 3: 1,054,000 DoFs) on 1, 2 and 4 ranks,
# on the fully distributed mesh. Four ranks are oversubscribed on a 2-core
# machine: their memory counts, their speed does not. Prints
# `ranks,dofs,peak_memory_mb_per_rank,step_seconds,iterations`: the peak
# resident memory of the largest rank (the program's own report), the
# seconds and FGMRES iterations of the second step (from rest the first
# solves the whole flow; the second is a small change, as in a coupled
# run), then the memory per rank of 2 ranks over that of 1; the rows are
# added to doc/results/benchmarks/fluid_scaling.csv (benchmarks/common.sh).
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "${1:-}" 1

cat > run.prm <<PRM
set Experiment = flow
set Output directory = out
subsection Geometry
  set Capillary length = 40
end
subsection Mesh
  set Fluid global refinements = 3
end
subsection Time
  set Time step = 1e-5
  set Number of steps = 2
  set Output interval = 1000
end
PRM
results_table fluid_scaling ranks DoFs "peak memory per rank [MB]" "step [s]" "FGMRES iterations"
for n in 1 2 4; do
  mpirun --oversubscribe -np "$n" "$exe" run.prm > log.txt
  dofs=$(sed -n 's/.* \([0-9]*\) DoFs (.*/\1/p' log.txt)
  memory=$(peak_memory log.txt)
  # the second step's wall time, from the progress lines' running wall clock
  step=$(sed -n 's/.*\[wall \([^],]*\).*/\1/p' log.txt | awk '
    { t = 0; for (i = 1; i < NF; i += 2) t += $i * ($(i + 1) == "h" ? 3600 : $(i + 1) == "min" ? 60 : 1) }
    NR == 1 {a = t} NR == 2 {printf "%.2f", t - a}')
  its=$(awk -F, 'NR == 3 {print $8}' out/flow.csv)
  echo "$n,$dofs,$memory,$step,$its" >>rows.csv
  results_row "$n" "$dofs" "$memory" "$step" "$its"
done
awk -F, '$1 == 1 {one = $3} $1 == 2 {two = $3} END {printf "memory per rank, 2 ranks over 1: %.2f\n", two / one}' rows.csv

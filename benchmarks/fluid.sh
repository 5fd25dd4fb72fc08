#!/usr/bin/env bash
# Usage: benchmarks/fluid.sh [RBC_IFEM] [RANKS] [REFINEMENTS...]
#
# The Stokes solver at three mesh sizes (fluid global refinements 1, 2, 3,
# or the ones given: 4 is 4.2 million DoFs, 3.2 GB a rank and 2 minutes on
# 2 ranks):
# DoFs, Q2 velocity nodes, the velocity multigrid's levels, setup (DoFs,
# constraints, the matrix-free operators, the multigrid hierarchy, its
# smoothers and coarse factorisation), and per time step the residual (one
# matrix-free pass), FGMRES seconds and iterations, for the first step from
# rest (the full problem) and a later step (a small change, as in a coupled
# run). Prints a Markdown table and adds its rows to
# doc/results/benchmarks/fluid.csv (benchmarks/common.sh). RBC_IFEM defaults
# to build/rbc-ifem, RANKS to 1.
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "${1:-}" "${2:-}"
levels=("${@:3}")
[ ${#levels[@]} -gt 0 ] || levels=(1 2 3)

results_table fluid ranks refinements DoFs "velocity nodes" "multigrid levels" "setup [s]" "step 1: FGMRES its" \
  "step 2: FGMRES its" "solve per iteration [ms]" "residual per step [ms]" "peak memory [MB]"
for level in "${levels[@]}"; do
  cat > run.prm <<PRM
set Experiment = flow
set Output directory = out
subsection Mesh
  set Fluid global refinements = $level
end
subsection Time
  set Time step = 1e-5
  set Number of steps = 2
  set Output interval = 1000
end
PRM
  /usr/bin/env time -f "%M" -o memory.txt mpirun -np "$ranks" "$exe" run.prm > log.txt
  dofs=$(sed -n 's/.* \([0-9]*\) DoFs (\([0-9]*\) velocity.*/\1 \2/p' log.txt)
  levels=$(sed -n 's/.*velocity multigrid: \([0-9]*\) levels.*/\1/p' log.txt)
  seconds() { awk -F, -v s="\"$1\"" '$1 == s {printf "%.2f", $3}' out/timing.csv; }
  its=$(awk -F, 'NR > 1 {printf "%s ", $8}' out/flow.csv)
  read -r its1 its2 <<<"$its"
  per_iteration=$(awk -F, -v n=$((its1 + its2)) '$1 == "\"fluid: solve\"" {printf "%.0f", 1000 * $3 / n}' out/timing.csv)
  residual=$(awk -F, '$1 == "\"fluid: residual\"" {printf "%.1f", 1000 * $3 / $2}' out/timing.csv)
  read -r n_dofs n_velocity <<<"$dofs"
  results_row "$ranks" "$level" "$n_dofs" $((n_velocity / 3)) "$levels" "$(seconds "fluid: setup")" "$its1" "$its2" \
    "$per_iteration" "$residual" $(($(cat memory.txt) / 1024))
done

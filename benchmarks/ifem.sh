#!/usr/bin/env bash
# Usage: benchmarks/ifem.sh [RBC_IFEM] [RANKS]
#
# The immersed time loop of prm/default.prm, shortened to 100 steps with
# two DM solves (at the start and at step 100), for membranes of 3 and 4
# surface refinements (Δt 2e-5 and 1.5e-5 s, below the explicit limits).
# Per run: membrane points, fluid DoFs, seconds per step, the shares of a
# step's time (fluid solve, fluid residual assembly, membrane forces, the
# coupling's spread + interpolate + move and place), seconds per diffusion
# solve (mesh, setup, assembly, solve, output). Prints a Markdown table and
# adds its rows to doc/results/benchmarks/ifem.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

results_table ifem ranks "surface refinements" "membrane points" "fluid DoFs" "s per step" "fluid solve" \
  "fluid residual" "membrane forces" coupling "s per DM solve"
for run in "3 2e-5" "4 1.5e-5"; do
  read -r level step <<<"$run"
  { cat "$here/prm/default.prm"
    cat <<PRM
set Output directory = out
subsection Cells
  set Surface refinements = $level
end
subsection Time
  set Time step       = $step
  set Number of steps = 100
  set Output interval = 100
end
subsection Immersed cells
  set Coupling            = explicit
  set Progress interval   = 20
  set Diffusion interval  = 100
  set Checkpoint interval = 0
end
PRM
  } > run.prm
  mpirun -np "$ranks" "$exe" run.prm > log.txt
  points=$(sed -n 's/.*cells: 1, \([0-9]*\) membrane points.*/\1/p' log.txt)
  dofs=$(sed -n 's/.*fluid mesh: [0-9]* cells, \([0-9]*\) DoFs.*/\1/p' log.txt)
  per_step=$(sed -n 's/.* steps in .* s, \(.*\) s per step/\1/p' log.txt)
  read -r -a shares < <(awk -F, -v per_step="$per_step" '
    NR > 1 { gsub(/"/, "", $1); t[$1] = $3; loop += ($1 ~ /^(fluid: solve|fluid: assemble residual|membrane forces|coupling)/) ? $3 : 0
             if ($1 ~ /^coupling/) coupling += $3
             if ($1 ~ /^diffusion/) diffusion += $3 }
    END { total = 100 * per_step
          printf "%.3f %.0f%% %.0f%% %.0f%% %.0f%% %.1f\n", per_step,
                 100 * t["fluid: solve"] / total, 100 * t["fluid: assemble residual"] / total,
                 100 * t["membrane forces"] / total, 100 * coupling / total, diffusion / 2 }' out/timing.csv)
  results_row "$ranks" "$level" "$points" "$dofs" "${shares[@]}"
done

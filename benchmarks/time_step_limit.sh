#!/usr/bin/env bash
# Usage: benchmarks/time_step_limit.sh [RBC_IFEM]
#
# Where the explicit coupling becomes unstable, against the estimate the
# program prints: prm/default.prm with membranes of 3 surface refinements,
# no DM solves, up to 300 steps, for the area dilation modulus K and time
# step of each row. Prints a Markdown table: the estimate, Δt over it, and
# the step at which the run stopped as diverged (or "stable"), and adds the
# rows to doc/results/benchmarks/time_step_limit.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

results_table time_step_limit "K [pN/µm]" "estimate [s]" "Δt [s]" "Δt / estimate" result
for run in "500 5e-6" "50 5e-5" "50 3.5e-5" "50 2e-5"; do
  read -r modulus step <<<"$run"
  { cat "$here/prm/default.prm"
    cat <<PRM
set Output directory = out
subsection Cells
  set Surface refinements = 3
end
subsection Membrane
  set Area dilation modulus = $modulus
end
subsection Time
  set Time step       = $step
  set Number of steps = 300
  set Output interval = 300
end
subsection Immersed cells
  set Coupling            = explicit
  set Diffusion interval  = 0
  set Checkpoint interval = 0
  set Progress interval   = 100
end
PRM
  } > run.prm
  "$exe" run.prm > log.txt 2>&1 || true
  estimate=$(sed -n 's/.*time step limit ≈ \([^ ]*\) s.*/\1/p' log.txt)
  stopped=$(sed -n 's/^rbc-ifem: stopped: step \([0-9]*\),.*/\1/p' log.txt)
  result=${stopped:+diverges at step $stopped}
  results_row "$modulus" "$(awk -v e="$estimate" 'BEGIN { printf "%.2g", e }')" "$step" \
    "$(awk -v e="$estimate" -v dt="$step" 'BEGIN { printf "%.2f", dt / e }')" "${result:-stable, 300 steps}"
done

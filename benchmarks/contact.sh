#!/usr/bin/env bash
# Usage: benchmarks/contact.sh [RBC_IFEM] [RANKS]
#
# What the contact forces cost: seven cells clustered 0.2 µm apart (inside
# the repulsion range, so every neighbour pair interacts) in the 20 µm
# capillary at the default mesh of prm/default.prm (Surface refinements 4,
# 10,766 membrane points), 20 steps, run twice side by side: with the
# default Cell interactions (repulsion and wall) and aggregation on, and
# with every interaction off. Per run: seconds per step, the membrane
# forces' seconds per step (MembraneElasticity alone, or with the
# interactions) and the gap check's. The interactions' cost is the
# difference of the force times plus the gap check, printed as a share of
# the step of the run with them. The table's rows are added to
# doc/results/benchmarks/contact.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

run() {
  local name=$1 repulsion=$2 wall=$3 aggregation=$4
  { cat "$here/prm/default.prm"
    cat <<PRM
set Output directory = $name
subsection Layout
  set Kind            = clustered
  set Number of cells = 7
  set Minimum gap     = 0.2
end
subsection Time
  set Time step       = 1.5e-5
  set Number of steps = 20
  set Output interval = 20
end
subsection Immersed cells
  set Coupling            = explicit
  set Progress interval   = 20
  set Diffusion interval  = 0
  set Checkpoint interval = 0
end
subsection Cell interactions
  set Repulsion pressure = $repulsion
  set Wall pressure      = $wall
  set Aggregation        = $aggregation
end
PRM
  } > $name.prm
  mpirun -np "$ranks" "$exe" $name.prm > $name.log
}
run with 10 10 true
run without 0 0 false

results_table contact ranks run "membrane points" "s per step" "membrane forces [s per step]" "gap check [s per step]"
for name in with without; do
  points=$(sed -n 's/.*cells: 7, \([0-9]*\) membrane points.*/\1/p' $name.log)
  per_step=$(sed -n 's/.* steps in .* s, \(.*\) s per step/\1/p' $name.log)
  read -r forces check < <(awk -F, 'NR > 1 { gsub(/"/, "", $1); t[$1] = $3 }
    END { printf "%.4f %.4f\n", t["membrane forces"] / 20, t["contact check"] / 20 }' $name/timing.csv)
  results_row "$ranks" "$name interactions" "$points" "$(printf '%.3f' "$per_step")" "$forces" "$check"
done
awk -F, 'FNR == 1 { file++ } FNR > 1 { gsub(/"/, "", $1); t[file, $1] = $3 }
         END { extra = (t[1, "membrane forces"] - t[2, "membrane forces"]) / 20
               check = t[1, "contact check"] / 20
               printf "\ninteraction forces %.4f s and gap check %.4f s per step\n", extra, check }' with/timing.csv without/timing.csv
per_step=$(sed -n 's/.* steps in .* s, \(.*\) s per step/\1/p' with.log)
awk -F, -v per_step="$per_step" 'FNR == 1 { file++ } FNR > 1 { gsub(/"/, "", $1); t[file, $1] = $3 }
     END { printf "share of a step with interactions: forces %.1f%%, gap check %.1f%%, together %.1f%%\n",
                  100 * (t[1, "membrane forces"] - t[2, "membrane forces"]) / 20 / per_step,
                  100 * t[1, "contact check"] / 20 / per_step,
                  100 * ((t[1, "membrane forces"] - t[2, "membrane forces"]) / 20 + t[1, "contact check"] / 20) / per_step }' \
  with/timing.csv without/timing.csv

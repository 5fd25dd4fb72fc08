#!/usr/bin/env bash
# Usage: benchmarks/paper_size_step.sh RANKS RBC_IFEM [RBC_IFEM...]
#
# The warm coupled step at the paper's resolution (prm/default.prm with
# Fluid band refinements = 2, Band width = 2.5, Surface refinements = 5,
# explicit, Δt = 4e-6 s: 244,862 DoFs, 6,146 membrane points): the wall
# time from the progress line of step 5 to that of step 25 of one run, over
# 20 (it includes three progress lines' flow measures, about 8 ms a step;
# unlike step70_anchor.sh's difference of two runs it leaves out the set-up,
# whose time varies from run to run). For each program given, one after the
# other in the same run, so that two builds (before and after a change)
# compare side by side on the same machine load. Prints per program the
# seconds per warm step, the FGMRES iterations of steps 5 to 25 as the
# progress lines give them, and the membrane forces' seconds per step, and
# adds the rows to doc/results/benchmarks/paper_size_step.csv
# (benchmarks/common.sh) with the git commit each program was built from.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
ranks=${1:?usage: paper_size_step.sh RANKS RBC_IFEM [RBC_IFEM...]}
shift
programs=()
for program in "$@"; do programs+=("$(realpath "$program")"); done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# run PROGRAM OUTPUT: 25 steps, a progress line every fifth
run() {
  mpirun -np "$ranks" "$1" "$here/prm/default.prm" \
    --set "Mesh/Fluid band refinements=2" --set "Mesh/Band width=2.5" \
    --set "Cells/Surface refinements=5" --set "Immersed cells/Coupling=explicit" \
    --set "Time/Time step=4e-6" --set "Time/Number of steps=25" \
    --set "Immersed cells/Diffusion interval=0" \
    --set "Immersed cells/Progress interval=5" \
    --set "Immersed cells/Checkpoint interval=0" \
    --set "Time/Output interval=1000" --set "Output directory=$2" > "$2.log" 2>&1
}
results_table paper_size_step program "built from" ranks "warm step [s]" \
  "FGMRES iterations at steps 5, 10, ..., 25" "membrane forces per step [s]"
for program in "${programs[@]}"; do
  run "$program" out
  warm=$(sed -n 's/.*step \(5\|25\) of 25.*\[wall \([0-9.]*\) s.*/\2/p' out.log |
    awk 'NR == 1 {a = $1} NR == 2 {printf "%.3f", ($1 - a) / 20}')
  iterations=$(awk -F, 'NR > 1 {printf "%s%s", sep, $8; sep = " "}' out/flow.csv)
  forces=$(awk -F, '$1 == "\"membrane forces\"" {printf "%.3f", $3 / $2}' out/timing.csv)
  results_row "$program" "$("$program" --version | sed -n 's/.*(git \(.*\)).*/\1/p')" "$ranks" "$warm" \
    "$iterations" "$forces"
  rm -rf out
done

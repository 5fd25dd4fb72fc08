#!/usr/bin/env bash
# Usage: benchmarks/paper_size_step.sh RANKS RBC_IFEM [RBC_IFEM...]
#
# The warm coupled step at the paper's resolution (prm/default.prm with
# Fluid band refinements = 2, Band width = 2.5, Surface refinements = 5,
# explicit, Δt = 4e-6 s: 244,862 DoFs, 6,146 membrane points), as
# step70_anchor.sh measures it: the difference of a 25-step and a 5-step run
# over 20. For each program given, one after the other in the same run, so
# that two builds (before and after a change) compare side by side on the
# same machine load. Prints per program the seconds per warm step and the
# membrane forces' seconds per step (timing.csv of the 25-step run).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
ranks=${1:?usage: paper_size_step.sh RANKS RBC_IFEM [RBC_IFEM...]}
shift
programs=()
for program in "$@"; do programs+=("$(realpath "$program")"); done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# run PROGRAM STEPS OUTPUT: the wall seconds of the run
run() {
  /usr/bin/env time -f "%e" -o t.txt mpirun -np "$ranks" "$1" "$here/prm/default.prm" \
    --set "Mesh/Fluid band refinements=2" --set "Mesh/Band width=2.5" \
    --set "Cells/Surface refinements=5" --set "Immersed cells/Coupling=explicit" \
    --set "Time/Time step=4e-6" --set "Time/Number of steps=$2" \
    --set "Immersed cells/Diffusion interval=0" \
    --set "Immersed cells/Progress interval=1000" \
    --set "Immersed cells/Checkpoint interval=0" \
    --set "Time/Output interval=1000" --set "Output directory=$3" > "$3.log" 2>&1
  cat t.txt
}
echo "| program | ranks | warm step [s] | membrane forces per step [s] |"
echo "|---|---|---|---|"
for program in "${programs[@]}"; do
  few=$(run "$program" 5 few)
  more=$(run "$program" 25 more)
  forces=$(awk -F, '$1 == "\"membrane forces\"" {printf "%.3f", $3 / $2}' more/timing.csv)
  awk -v p="$program" -v r="$ranks" -v a="$few" -v b="$more" -v f="$forces" \
    'BEGIN { printf "| %s | %d | %.3f | %s |\n", p, r, (b - a) / 20, f }'
  rm -rf few more
done

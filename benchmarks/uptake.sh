#!/usr/bin/env bash
# Usage: benchmarks/uptake.sh BEFORE AFTER [RANKS] [CELLS]
#
# One DM solve on cut cells (Q2, band refinements 1, membranes at Surface
# refinements 4: the default mesh of the flowing runs), by two rbc-ifem
# programs side by side in one run of this script (the machine is shared:
# ratios of one run hold, absolute times of another day do not):
# - one resting cell in the default 20 µm capillary (prm/default.prm's
#   geometry, open ends);
# - seven uniform cells in the periodic segment, the first DM instant of
#   each seven-cell run of prm/flowing_layouts.prm;
# - with CELLS, CELLS uniform cells in a periodic segment of 5 CELLS µm
#   (benchmarks/scaling.sh's trains), where what every rank holds of the
#   mesh shows.
# Each solve runs three times per program and the fastest is kept. Prints
# the TimerOutput seconds of each phase, the total of the solve (mesh,
# setup, assembly, solve), AFTER over BEFORE, and whether the two
# programs' dm.csv agree to the last digit. Then prm/default.prm whole by
# each program: its wall time, the fluid solve, the 11 DM instants, and the
# largest difference of DM(t). The rows go to
# doc/results/benchmarks/uptake.csv and uptake_default_run.csv
# (benchmarks/common.sh). RANKS defaults to 1.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
before=$(realpath "$1")
benchmark_setup "$2" "${3:-1}"
results_setup "$@"

phases=("diffusion mesh" "diffusion: level set" "diffusion: surface points" "diffusion: DoFs and constraints"
  "diffusion: sparsity" "diffusion: assemble" "diffusion: AMG setup" "diffusion: solve")
# solve NAME PROGRAM SETTINGS...: the fastest of three runs of PROGRAM into
# NAME/ (its timing.csv and dm.csv), with --set SETTINGS.
solve() {
  local name=$1 program=$2 run
  shift 2
  local -a sets=()
  for s in "$@"; do sets+=(--set "$s"); done
  for run in 1 2 3; do
    mpirun -np "$ranks" "$program" "$here/prm/default.prm" --set "Experiment=diffusion" \
      --set "Output directory=$name.$run" "${sets[@]}" >"$name.$run.log"
  done
  best=$(for run in 1 2 3; do echo "$(uptake_seconds "$name.$run") $run"; done | sort -g | head -1 | cut -d' ' -f2)
  cp -r "$name.$best" "$name"
  cp "$name.$best.log" "$name.log"
}

# peak_memory NAME WHICH: the peak resident memory [MB] of rank 0 (WHICH
# = first) or of the largest other rank (others) in NAME.log's last line.
peak_memory() {
  sed -n 's/.*peak memory: \([0-9.]*\) MB (largest over ranks\(; rank 0 \([0-9.]*\) MB, the others [0-9.]*-\([0-9.]*\) MB\)\{0,1\}).*/\1 \3 \4/p' "$1.log" |
    awk -v w="$2" '{ print (NF == 1 ? $1 : (w == "first" ? $2 : $3)) }'
}

cut_cells=("Diffusion/Method=cut cell" "Diffusion/Finite element degree=2" "Mesh/Diffusion band refinements=1")
seven=("Geometry/Periodic=true" "Layout/Number of cells=7")

# compare LABEL SETTINGS...: the two programs on one case.
compare() {
  local label=$1 phase a b same
  shift
  solve before "$before" "${cut_cells[@]}" "$@"
  solve after "$exe" "${cut_cells[@]}" "$@"
  for phase in "${phases[@]}"; do
    b=$(section_seconds before "$phase") a=$(section_seconds after "$phase")
    results_row "$ranks" "$label" "${phase#diffusion: }" "$b" "$a" \
      "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", (b > 0 ? a / b : 0) }')"
  done
  b=$(uptake_seconds before) a=$(uptake_seconds after)
  results_row "$ranks" "$label" "whole solve" "$b" "$a" "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", a / b }')"
  for which in first others; do
    [ "$which" = others ] && [ "$ranks" = 1 ] && continue
    b=$(peak_memory before $which) a=$(peak_memory after $which)
    results_row "$ranks" "$label" "peak memory, $([ $which = first ] && echo "rank 0" || echo "largest other rank") [MB]" \
      "$b" "$a" "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f", a / b }')"
  done
  if cmp -s before/dm.csv after/dm.csv; then
    same="the same to the last digit"
  else
    same="DIFFERENT: $(tail -1 before/dm.csv) against $(tail -1 after/dm.csv)"
  fi
  echo "($label: dm.csv of the two programs $same)"
  rm -rf before* after*
}

results_table uptake ranks case phase "before [s]" "after [s]" "after / before"
compare "one cell"
compare "seven cells, periodic" "${seven[@]}"
if [ -n "${4:-}" ]; then
  compare "$4 cells, periodic $((5 * $4)) µm" "Geometry/Periodic=true" "Layout/Number of cells=$4" \
    "Geometry/Capillary length=$((5 * $4))"
fi

echo
echo "## prm/default.prm on $ranks rank(s)"
echo
results_table uptake_default_run ranks measure "before" "after" "after / before"
for program in before after; do
  [ $program = before ] && p=$before || p=$exe
  mpirun -np "$ranks" "$p" "$here/prm/default.prm" --set "Output directory=$program" >"$program.log"
done
wall() { sed -n 's/.* steps in \(.*\), .* s per step$/\1/p' "$1.log" | awk '{ t = 0; for (i = 1; i <= NF; i += 2) t += $i * ($(i + 1) == "min" ? 60 : 1); printf "%.1f", t }'; }
diffusion() { printf '%.2f' "$(uptake_seconds "$1" '"diffusion: output"')"; }
instants() { awk 'END { print NR - 1 }' "$1/dm.csv"; }
ratio() { awk -v a="$2" -v b="$1" 'BEGIN { printf "%.2f", a / b }'; }
b=$(wall before) a=$(wall after)
results_row "$ranks" "wall [s]" "$b" "$a" "$(ratio "$b" "$a")"
b=$(section_seconds before "fluid: solve") a=$(section_seconds after "fluid: solve")
results_row "$ranks" "fluid solve [s]" "$b" "$a" "$(ratio "$b" "$a")"
b=$(diffusion before) a=$(diffusion after)
results_row "$ranks" "DM solves with their output, start-up check aside [s]" "$b" "$a" "$(ratio "$b" "$a")"
b=$(awk -v t="$b" -v n="$(instants before)" 'BEGIN { printf "%.3f", t / n }')
a=$(awk -v t="$a" -v n="$(instants after)" 'BEGIN { printf "%.3f", t / n }')
results_row "$ranks" "per DM instant [s]" "$b" "$a" "$(ratio "$b" "$a")"
largest=$(paste -d, before/dm.csv after/dm.csv | awk -F, 'NR > 1 { n = NF / 2; d = $(n + 2) / $2 - 1; d = d < 0 ? -d : d; if (d > m) m = d } END { printf "%.1e", m }')
echo "(DM(t) of the two runs: the largest relative difference $largest)"

#!/usr/bin/env bash
# Usage: benchmarks/finite_uptake.sh [RBC_IFEM] [RANKS]
#
# DL with CO bound inside the cells (Diffusion/Uptake = reaction,
# doc/physiology.md) at θ_CO of Guénard et al. 2016 at PO₂ = 100 Torr, on
# the mesh of prm/finite_uptake.prm (Surface refinements 4, band refinements
# 1, cut cells Q2), with two tables:
# 1. mesh convergence: one cell at band refinements 1, 2 and 3, seven
#    uniform cells at 1 and 2 (3 would need about 20 GB): DM, DL, DL's
#    difference from the finest, seconds of the whole experiment and the
#    peak memory of the largest rank;
# 2. the cytoplasm's diffusivity (one cell): DL at 1/4, 2/7 (the default,
#    700 µm²/s), 1 and 10 times the plasma's 2453 µm²/s, beside the lumped
#    1/DM + 1/(θ V_c), which assumes the cell's inside well mixed.
# The rows are added to doc/results/benchmarks/finite_uptake_mesh.csv and
# finite_uptake_cytoplasm.csv (benchmarks/common.sh). RBC_IFEM defaults to
# build/rbc-ifem, RANKS to 1.
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"
prm=$(dirname "$exe")/../prm/finite_uptake.prm
[ -f "$prm" ] || prm=$(cd "$(dirname "$0")/.." && pwd)/prm/finite_uptake.prm

# run N BAND DIFFUSIVITY: "DM DL lumped seconds" for N uniform cells.
run() {
  local start end
  start=$(date +%s.%N)
  mpirun -np "$ranks" "$exe" "$prm" \
    --set "Output directory=out" \
    --set "Layout study/Kinds=uniform" --set "Layout study/Numbers of cells=$1" \
    --set "Finite uptake/Theta models=Guenard 2016" \
    --set "Finite uptake/Oxygen pressures=100" --set "Finite uptake/Thetas=" \
    --set "Mesh/Diffusion band refinements=$2" \
    --set "Diffusion/Cytoplasm diffusivity=$3" > log.txt
  end=$(date +%s.%N)
  awk -F, -v s="$(echo "$end - $start" | bc)" \
    'NR == 2 { printf "%.6f %.6f %.6f %.1f\n", $8, $9, $10, s }' out/uptake.csv
}

results_table finite_uptake_mesh ranks cells "band refinements" DM DL "DL / DL(finest) - 1" seconds "peak memory [MB]"
for n in 1 7; do
  bands="1 2 3"
  [ "$n" = 1 ] || bands="1 2"
  rows=()
  for band in $bands; do
    read -r dm d lumped seconds <<<"$(run "$n" "$band" 700)"
    finest=$d
    rows+=("$n $band $dm $d $seconds $(sed -n 's/.*peak memory: \([0-9.e+]*\) MB.*/\1/p' log.txt)")
  done
  for row in "${rows[@]}"; do
    read -r cells band dm d seconds memory <<<"$row"
    results_row "$ranks" "$cells" "$band" "$dm" "$d" "$(awk -v a="$d" -v b="$finest" 'BEGIN { printf "%+.3f%%", 100 * (a / b - 1) }')" \
      "$seconds" "$memory"
  done
done

echo
results_table finite_uptake_cytoplasm ranks "cytoplasm D [µm²/s]" DM DL "lumped 1/DM + 1/(θ V_c)" "lumped / DL - 1"
for diffusivity in 613 700 2453 24530; do
  read -r dm d lumped seconds <<<"$(run 1 1 "$diffusivity")"
  results_row "$ranks" "$diffusivity" "$dm" "$d" "$lumped" "$(awk -v a="$lumped" -v b="$d" 'BEGIN { printf "%+.1f%%", 100 * (a / b - 1) }')"
done

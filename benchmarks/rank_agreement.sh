#!/usr/bin/env bash
# Usage: benchmarks/rank_agreement.sh [RBC_IFEM]
#
# How far DM on 2, 3 and 4 ranks (oversubscribed on a smaller machine) is
# from DM on one, at two Diffusion/Linear solver tolerances, the default
# 1e-8 and 1e-10: prm/default.prm for one step, DM of t = 0 from dm.csv
# (all its digits), and the flow rate of step 1 from flow.csv. Prints a
# Markdown table and adds its rows to doc/results/benchmarks/
# rank_agreement.csv (benchmarks/common.sh). About 1 minute.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "${1:-}" 1
export OMPI_MCA_rmaps_base_oversubscribe=1

results_table rank_agreement "diffusion tolerance" ranks "DM at t = 0 [µm³ s⁻¹ Torr⁻¹]" \
  "DM / DM on 1 rank - 1" "flow rate, step 1 [µm³/s]" "flow rate / on 1 rank - 1"
for tolerance in 1e-8 1e-10; do
  for n in 1 2 3 4; do
    rm -rf out
    mpirun -np "$n" "$exe" "$here/prm/default.prm" --set "Output directory=out" \
      --set "Time/Number of steps=1" --set "Diffusion/Linear solver tolerance=$tolerance" \
      --set "Immersed cells/Checkpoint interval=0" >log.txt 2>&1 || { tail -5 log.txt; exit 1; }
    dm=$(awk -F, 'NR == 2 { print $2 }' out/dm.csv)
    flow=$(awk -F, 'NR == 2 { print $2 }' out/flow.csv)
    [ "$n" -eq 1 ] && { dm1=$dm; flow1=$flow; }
    results_row "$tolerance" "$n" "$dm" "$(awk -v a="$dm" -v b="$dm1" 'BEGIN { printf "%.1e", a / b - 1 }')" \
      "$flow" "$(awk -v a="$flow" -v b="$flow1" 'BEGIN { printf "%.1e", a / b - 1 }')"
  done
done

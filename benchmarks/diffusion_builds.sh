#!/usr/bin/env bash
# Usage: benchmarks/diffusion_builds.sh BEFORE AFTER [REPEATS] [RANKS]
#
# Two builds of rbc-ifem side by side on issue 21's timed case: one CO
# diffusion solve of seven uniform cells with cut cells (Q2, Surface
# refinements 4, band refinements 1), the two builds alternated REPEATS
# times (default 5) on RANKS ranks (default 2), so that the machine's
# changing load falls on both alike. Prints one Markdown row per run: the
# total without output (as benchmarks/diffusion.sh counts it) and its
# TimerOutput sections [s], and whether the run's dm.csv matches the first
# run's of BEFORE to the last digit; the rows are added to
# doc/results/benchmarks/diffusion_builds.csv (benchmarks/common.sh) with
# the git commit each build was made from (its --version).
set -euo pipefail
before=$(realpath "$1")
after=$(realpath "$2")
repeats=${3:-5}
source "$(dirname "$0")/common.sh"
benchmark_setup "$before" "${4:-2}"

write_seven_cells_prm "cut cell" 2 4 1

results_table diffusion_builds ranks build "built from" "total without output" mesh "level set" "surface points" \
  sparsity assembly "of it: AMG setup" solve "dm.csv as the first"
for _ in $(seq "$repeats"); do
  for build in "$before" "$after"; do
    mpirun -np "$ranks" "$build" run.prm > log.txt
    [ -f reference.csv ] || cp out/dm.csv reference.csv
    same=$(cmp -s out/dm.csv reference.csv && echo yes || echo no)
    label=$([ "$build" = "$before" ] && echo before || echo after)
    built_from=$("$build" --version | sed -n 's/.*(git \(.*\)).*/\1/p')
    read -r -a seconds < <(awk -F, 'NR > 1 { gsub(/"/, "", $1); t[$1] += $3 }
      END { printf "%.2f %.2f %.2f %.2f %.2f %.2f %.2f %.2f\n",
              t["diffusion mesh"] + t["diffusion: setup"] + t["diffusion: membrane sampling"] + t["diffusion: assemble"] + t["diffusion: solve"],
              t["diffusion mesh"], t["diffusion: level set"], t["diffusion: surface points"], t["diffusion: sparsity"],
              t["diffusion: assemble"], t["diffusion: AMG setup"], t["diffusion: solve"] }' out/timing.csv)
    results_row "$ranks" "$label" "$built_from" "${seconds[@]}" "$same"
  done
done

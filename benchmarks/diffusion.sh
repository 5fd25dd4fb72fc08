#!/usr/bin/env bash
# Usage: benchmarks/diffusion.sh [RBC_IFEM] [RANKS]
#
# One CO diffusion solve of seven uniform cells (the full capillary), side by
# side: the Lagrange multiplier on the meshes of levels 2 and 3 of
# prm/mesh_convergence.prm (membrane and band refinements 3 and 4), and cut
# cells (Q2, membranes at Surface refinements 4) at band refinements 1 and 2
# (doc/diffusion.md). Prints a Markdown table: DoFs, solver iterations, DM,
# and the TimerOutput seconds of mesh, setup (with the cut cells' sampling
# of the membranes; of it: locating the membrane points, or the level set),
# assembly (of it: AMG setup), solve and output,
# with the peak memory of the largest rank. A second table: the cut cells'
# DM and CG iterations at band refinements 1 and 2 against the weight of the
# ghost penalty (Diffusion/Ghost penalty). The rows are added to
# doc/results/benchmarks/diffusion.csv and diffusion_ghost_penalty.csv
# (benchmarks/common.sh). RBC_IFEM defaults to build/rbc-ifem, RANKS to 1.
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

# solve_summary: "DoFs iterations DM" from the run's log.txt.
solve_summary() {
  sed -n 's/.*: \([0-9]*\) DoFs, \([0-9]*\) solver iterations.*DM \([0-9.]*\) .*/\1 \2 \3/p' log.txt
}

results_table diffusion ranks method "surface, band refinements" DoFs "solver its" "DM [µm³ s⁻¹ Torr⁻¹]" "mesh [s]" \
  "setup [s]" "of it: point location or level set [s]" "assembly [s]" "of it: AMG setup [s]" "solve [s]" \
  "total without output [s]" "output [s]" "peak memory [MB]"
for run in "Lagrange multiplier:1:3:3" "Lagrange multiplier:1:4:4" "cut cell:2:4:1" "cut cell:2:4:2"; do
  IFS=: read -r method degree surface band <<<"$run"
  write_seven_cells_prm "$method" "$degree" "$surface" "$band"
  /usr/bin/env time -f "%M" -o memory.txt mpirun -np "$ranks" "$exe" run.prm > log.txt
  read -r dofs its dm <<<"$(solve_summary)"
  seconds() { awk -F, -v s="\"$1\"" '$1 == s {t += $3} END {printf "%.2f", t}' out/timing.csv; }
  located=$(awk -F, '$1 ~ /"diffusion: point location"|"diffusion: level set"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  setup=$(awk -F, '$1 ~ /"diffusion: setup"|"diffusion: membrane sampling"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  total=$(awk -F, '$1 ~ /"diffusion mesh"|"diffusion: setup"|"diffusion: membrane sampling"|"diffusion: assemble"|"diffusion: solve"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  results_row "$ranks" "$method" "$surface, $band" "$dofs" "$its" "$dm" "$(seconds "diffusion mesh")" "$setup" "$located" \
    "$(seconds "diffusion: assemble")" "$(seconds "diffusion: AMG setup")" "$(seconds "diffusion: solve")" "$total" \
    "$(seconds "diffusion: output")" $(($(cat memory.txt) / 1024))
done

# The ghost penalty's weight against the cut cells' DM and CG iterations
# (doc/diffusion.md, "Parameters"): 13.971 is the limit.
echo
results_table diffusion_ghost_penalty ranks "ghost penalty" "band refinements" DoFs "CG its" "DM [µm³ s⁻¹ Torr⁻¹]" "from 13.971"
for band in 1 2; do
  write_seven_cells_prm "cut cell" 2 4 "$band"
  for ghost in 0.05 0.02 0.01 0.005 0.002; do
    mpirun -np "$ranks" "$exe" run.prm --set "Diffusion/Ghost penalty=$ghost" > log.txt
    read -r dofs its dm <<<"$(solve_summary)"
    results_row "$ranks" "$ghost" "$band" "$dofs" "$its" "$dm" "$(awk -v d="$dm" 'BEGIN { printf "%+.3f%%", 100 * (d / 13.971 - 1) }')"
  done
done

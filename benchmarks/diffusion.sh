#!/usr/bin/env bash
# Usage: benchmarks/diffusion.sh [RBC_IFEM] [RANKS]
#
# One CO diffusion solve of seven uniform cells (the full capillary) on the
# meshes of levels 2 and 3 of prm/mesh_convergence.prm (membrane and band
# refinements 3 and 4). Prints a Markdown table: DoFs, FGMRES iterations,
# and the TimerOutput seconds of mesh, setup (of it: locating the membrane
# points), assembly (of it: AMG setup), solve and output, with the peak
# memory of the largest rank. RBC_IFEM defaults to build/rbc-ifem, RANKS to 1.
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

echo "| refinements | DoFs | FGMRES its | mesh [s] | setup [s] | of it: point location [s] | assembly [s] | of it: AMG setup [s] | solve [s] | total without output [s] | output [s] | peak memory [MB] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for level in 3 4; do
  cat > run.prm <<PRM
set Experiment = diffusion
set Output directory = out
subsection Layout
  set Kind = uniform
  set Number of cells = 7
end
subsection Cells
  set Surface refinements = $level
end
subsection Mesh
  set Diffusion global refinements = 1
  set Diffusion band refinements = $level
end
PRM
  /usr/bin/env time -f "%M" -o memory.txt mpirun -np "$ranks" "$exe" run.prm > log.txt
  read -r dofs its <<<"$(sed -n 's/.*: \([0-9]*\) DoFs, \([0-9]*\) FGMRES.*/\1 \2/p' log.txt)"
  seconds() { awk -F, -v s="\"$1\"" '$1 == s {printf "%.2f", $3}' out/timing.csv; }
  total=$(awk -F, '$1 ~ /"diffusion mesh"|"diffusion: setup"|"diffusion: assemble"|"diffusion: solve"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  echo "| $level | $dofs | $its | $(seconds "diffusion mesh") | $(seconds "diffusion: setup") | $(seconds "diffusion: point location") | $(seconds "diffusion: assemble") | $(seconds "diffusion: AMG setup") | $(seconds "diffusion: solve") | $total | $(seconds "diffusion: output") | $(( $(cat memory.txt) / 1024 )) |"
done

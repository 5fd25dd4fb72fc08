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
# with the peak memory of the largest rank. RBC_IFEM defaults to
# build/rbc-ifem, RANKS to 1.
set -euo pipefail
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

echo "| method | surface, band refinements | DoFs | solver its | DM [µm³ s⁻¹ Torr⁻¹] | mesh [s] | setup [s] | of it: point location or level set [s] | assembly [s] | of it: AMG setup [s] | solve [s] | total without output [s] | output [s] | peak memory [MB] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for run in "Lagrange multiplier:1:3:3" "Lagrange multiplier:1:4:4" "cut cell:2:4:1" "cut cell:2:4:2"; do
  IFS=: read -r method degree surface band <<<"$run"
  cat > run.prm <<PRM
set Experiment = diffusion
set Output directory = out
subsection Layout
  set Kind = uniform
  set Number of cells = 7
end
subsection Cells
  set Surface refinements = $surface
end
subsection Mesh
  set Diffusion global refinements = 1
  set Diffusion band refinements = $band
end
subsection Diffusion
  set Method = $method
  set Finite element degree = $degree
end
PRM
  /usr/bin/env time -f "%M" -o memory.txt mpirun -np "$ranks" "$exe" run.prm > log.txt
  read -r dofs its dm <<<"$(sed -n 's/.*: \([0-9]*\) DoFs, \([0-9]*\) solver iterations.*DM \([0-9.]*\) .*/\1 \2 \3/p' log.txt)"
  seconds() { awk -F, -v s="\"$1\"" '$1 == s {t += $3} END {printf "%.2f", t}' out/timing.csv; }
  located=$(awk -F, '$1 ~ /"diffusion: point location"|"diffusion: level set"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  setup=$(awk -F, '$1 ~ /"diffusion: setup"|"diffusion: membrane sampling"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  total=$(awk -F, '$1 ~ /"diffusion mesh"|"diffusion: setup"|"diffusion: membrane sampling"|"diffusion: assemble"|"diffusion: solve"/ {t += $3} END {printf "%.2f", t}' out/timing.csv)
  echo "| $method | $surface, $band | $dofs | $its | $dm | $(seconds "diffusion mesh") | $setup | $located | $(seconds "diffusion: assemble") | $(seconds "diffusion: AMG setup") | $(seconds "diffusion: solve") | $total | $(seconds "diffusion: output") | $(( $(cat memory.txt) / 1024 )) |"
done

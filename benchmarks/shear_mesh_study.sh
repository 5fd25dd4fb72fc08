#!/usr/bin/env bash
# Usage: benchmarks/shear_mesh_study.sh [RBC_IFEM [RANKS]]
#
# The mesh study of the capsule in shear (doc/validation.md): the steady
# Taylor deformation at Ca = 0.15 (0.05 in the references' units, published
# 0.258-0.277) from prm/shear_capsule.prm, for two fluid resolutions at the
# capsule (Mesh/Fluid band refinements 1 and 2: h = a/2 and a/4) and two
# membrane resolutions (Cells/Surface refinements 3 and 4: 384 and 1536
# quadrilaterals), and in a box of 12a instead of 8a (the walls and the
# open ends farther away). Prints a Markdown table and adds its rows to
# doc/results/benchmarks/shear_mesh_study.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

results_table shear_mesh_study ranks "box [µm]" "fluid h at the capsule [µm]" "membrane points" "spacing [µm]" steps \
  "steady D" "steady θ/π" "wall time [s]"
for run in "1 3 24" "1 4 24" "2 3 24" "2 4 24" "1 3 36"; do
  read -r band surface box <<<"$run"
  rm -rf out # the runs of a study end with checkpoints, which a new run would not replace
  { cat "$here/prm/shear_capsule.prm"
    cat <<PRM
set Output directory = out
subsection Cells
  set Surface refinements = $surface
end
subsection Mesh
  set Fluid band refinements = $band
end
subsection Shear
  set Capillary numbers = 0.15
  set Box size          = $box, $box, $box
end
PRM
  } > run.prm
  OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -np "$ranks" "$exe" run.prm > log.txt 2>&1
  h=$(sed -n 's/.*fluid mesh size at the cells h = \([^ ]*\) µm.*/\1/p' log.txt)
  points=$(sed -n 's/^  cells: 1, \([0-9]*\) membrane points, spacing up to \([^ ]*\) µm.*/\1 \2/p' log.txt)
  read -r -a row < <(tail -n 1 out/shear_summary.csv | awk -F, -v b="$box" -v h="$h" -v p="$points" \
    'BEGIN { split(p, q, " ") } { printf "%s %s %s %.3g %d %.4f %.4f %.0f\n", b, h, q[1], q[2], $7, $2, $3, $8 }')
  results_row "$ranks" "${row[@]}"
done

#!/usr/bin/env bash
# Usage: benchmarks/sphere_in_tube.sh [RBC_IFEM [RANKS]]
#
# The nearly rigid sphere on the axis of the capillary (doc/validation.md):
# runs prm/sphere_in_tube_{free,held}_{0.3,0.5}.prm, and for λ = 0.5 again
# on a fluid mesh twice as fine at the sphere (Mesh/Fluid band refinements
# 2, membrane points and time step halved with it). Prints a Markdown
# table against Haberman & Sayre (1958) and the body-fitted solution
# (sphere-in-tube-reference): the free sphere's velocity over the
# centre-line velocity U/U_c, and the drag on the held sphere over
# 6πμaU_c, with U_c = 2ū = 1000 µm/s and μ = 1.2e-3 pN s/µm². The rows are
# added to doc/results/benchmarks/sphere_in_tube.csv (benchmarks/common.sh).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"

# run CASE LEVEL: prm/sphere_in_tube_CASE.prm, refined LEVEL - 1 more times.
run() {
  local refine=$(($2 - 1))
  { sed "s|^set Output directory.*|set Output directory = out|" "$here/prm/sphere_in_tube_$1.prm"
    if [ "$refine" -gt 0 ]; then
      awk -v r="$refine" '
        /set Surface refinements/ { s = $NF } /set Time step / { dt = $NF } /set Number of steps/ { n = $NF }
        /set Output interval/ { o = $NF }
        END { f = 2^r
              printf "subsection Cells\n  set Surface refinements = %d\nend\n", s + r
              printf "subsection Mesh\n  set Fluid band refinements = %d\nend\n", 1 + r
              printf "subsection Time\n  set Time step = %g\n  set Number of steps = %d\n  set Output interval = %d\nend\n", dt / f, n * f, o * f }' \
        "$here/prm/sphere_in_tube_$1.prm"
    fi
  } > run.prm
  OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -np "$ranks" "$exe" run.prm > log.txt 2>&1
  h=$(sed -n 's/.*fluid mesh size at the cells h = \([^ ]*\) µm.*/\1/p' log.txt)
  awk -F, -v h="$h" 'FNR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
                     { u = $c["frame_velocity"]; f = $c["held_force_x"] } END { print h, u, f }' out/flow.csv
  rm -rf out
}

results_table sphere_in_tube ranks "λ = a/R" "fluid h at the sphere [µm]" U/U_c "U/U_c, Haberman-Sayre" \
  "U/U_c, body-fitted" "U/U_c vs H-S" "U/U_c vs body-fitted" "F/(6πμaU_c)" "F/(6πμaU_c), Haberman-Sayre" \
  "F/(6πμaU_c), body-fitted" "F vs H-S" "F vs body-fitted"
for run in "0.3 1" "0.5 1" "0.5 2"; do
  read -r lambda level <<<"$run"
  read -r h velocity _ <<<"$(run "free_$lambda" "$level")"
  read -r _ _ force <<<"$(run "held_$lambda" "$level")"
  read -r _ body_held body_ratio <<<"$(body_fitted "$lambda")"
  read -r -a row < <(awk -v l="$lambda" -v h="$h" -v u="$velocity" -v f="$force" -v bh="$body_held" -v bu="$body_ratio" \
    "$haberman_sayre"'
  BEGIN {
    uc = 1000; mu = 1.2e-3; a = 5 * l; pi = 3.14159265358979
    g = hs_velocity_ratio(l); k = hs_drag_factor(l)
    ratio = u / uc; drag = -f / (6 * pi * mu * a * uc)
    printf "%s %s %.4f %.4f %.4f %+.1f%% %+.1f%% %.3f %.3f %.3f %+.1f%% %+.1f%%\n",
           l, h, ratio, g, bu, 100 * (ratio / g - 1), 100 * (ratio / bu - 1),
           drag, k * g, bh, 100 * (drag / (k * g) - 1), 100 * (drag / bh - 1) }')
  results_row "$ranks" "${row[@]}"
done

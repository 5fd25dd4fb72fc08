#!/usr/bin/env bash
# Usage: benchmarks/sphere_towed.sh [RBC_IFEM [RANKS [OUTPUT_DIRECTORY [LEVELS]]]]
#
# Where the free sphere's error comes from (doc/validation.md, Section 2):
# the λ = 0.5 sphere of prm/sphere_in_tube_held_0.5.prm held on the axis
# (a) in Poiseuille flow and (b) towed: no flow, the frame and so the walls
# moving past it at U = 1000 µm/s (Haberman & Sayre's drag factor K). By
# superposition the free sphere moves at U/U_c = F_held / F_towed. On three
# fluid meshes at the sphere, level L = 1, 2, 3: Mesh/Fluid band
# refinements L (h = 0.625, 0.3125, 0.15625 µm), Cells/Surface refinements
# L + 2 (386, 1538, 6146 points, about 0.8 h apart: any denser and the
# tethers' force creeps up for as long as a run lasts), the time step and
# the tether stiffness scaled with them, to t = 0.075 ms. LEVELS defaults
# to "1 2" (about 15 minutes on one core); "1 2 3" adds the finest (well
# over an hour more). Prints a Markdown table against Haberman & Sayre and
# the body-fitted solution (sphere-in-tube-reference), adds its rows to
# doc/results/benchmarks/sphere_towed.csv (benchmarks/common.sh), and keeps
# the runs in OUTPUT_DIRECTORY (default output/sphere_towed) for
# doc/scripts/plot_sphere_axis.py.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
out=$(realpath -m "${3:-$here/output/sphere_towed}")
levels=${4:-1 2}
source "$(dirname "$0")/common.sh"
benchmark_setup "$@"
mkdir -p "$out"

# run NAME LEVEL FLUID: prm/sphere_in_tube_held_0.5.prm on mesh LEVEL with
# the lines FLUID in subsection Fluid; prints held_force_x at the end.
run() {
  local name=$1 level=$2 fluid=$3
  local f=$((1 << (level - 1)))
  { sed "s|^set Output directory.*|set Output directory = $out/$name|" \
      "$here/prm/sphere_in_tube_held_0.5.prm"
    printf "subsection Fluid\n%b\nend\n" "$fluid"
    printf "subsection Mesh\n  set Fluid band refinements = %d\nend\n" "$level"
    printf "subsection Cells\n  set Surface refinements = %d\nend\n" $((level + 2))
    printf "subsection Immersed cells\n  set Tether stiffness = %g\nend\n" "$(awk -v f="$f" 'BEGIN { print 400 / f^2 }')"
    printf "subsection Time\n  set Time step = %g\n  set Number of steps = %d\n  set Output interval = %d\nend\n" \
      "$(awk -v f="$f" 'BEGIN { print 1.5e-6 / f }')" $((50 * f)) $((50 * f))
  } > "$name.prm"
  OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -np "$ranks" "$exe" "$name.prm" > "$name.log" 2>&1
  awk -F, 'FNR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } { f = $c["held_force_x"] } END { print f }' \
    "$out/$name/flow.csv"
}

read -r body_towed body_held body_ratio <<<"$(body_fitted 0.5)"
awk -v bk="$body_towed" -v bh="$body_held" -v bu="$body_ratio" "$haberman_sayre"'
BEGIN {
  g = hs_velocity_ratio(0.5); k = hs_drag_factor(0.5)
  printf "references at λ = 0.5: towed K %.3f (H-S), %.3f (body-fitted); held %.3f (H-S), %.3f (body-fitted); U/U_c %.4f (H-S), %.4f (body-fitted)\n\n",
         k, bk, k * g, bh, g, bu }'
results_table sphere_towed ranks "fluid h at the sphere [µm]" "membrane points" "towed F/(6πμaU)" "towed vs H-S" \
  "towed vs body-fitted" "held F/(6πμaU_c)" "held vs H-S" "held vs body-fitted" "U/U_c = F_held/F_towed" \
  "U/U_c vs H-S" "U/U_c vs body-fitted"
for level in $levels; do
  towed=$(run "towed_$level" "$level" "set Inlet mean speed = 0\nset Frame velocity = 1000")
  held=$(run "held_$level" "$level" "")
  read -r -a row < <(awk -v level="$level" -v towed="$towed" -v held="$held" \
      -v bk="$body_towed" -v bh="$body_held" -v bu="$body_ratio" "$haberman_sayre"'
  BEGIN {
    l = 0.5; u = 1000; mu = 1.2e-3; a = 2.5; pi = 3.14159265358979; f0 = 6 * pi * mu * a * u
    g = hs_velocity_ratio(l); k = hs_drag_factor(l)
    kt = towed / f0; kh = -held / f0; ratio = kh / kt
    printf "%s %d %.3f %+.1f%% %+.1f%% %.3f %+.1f%% %+.1f%% %.4f %+.1f%% %+.1f%%\n",
           0.625 / 2^(level - 1), 6 * 4^(level + 2) + 2,
           kt, 100 * (kt / k - 1), 100 * (kt / bk - 1), kh, 100 * (kh / (k * g) - 1), 100 * (kh / bh - 1),
           ratio, 100 * (ratio / g - 1), 100 * (ratio / bu - 1) }')
  results_row "$ranks" "${row[@]}"
done

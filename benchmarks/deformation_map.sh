#!/usr/bin/env bash
# Usage: benchmarks/deformation_map.sh [RBC_IFEM] [RANKS] [POINTS]
#
# The deformation and confinement map (doc/physiology.md): how much of its
# CO uptake one red cell of 7.5 µm loses as the flow deforms it, against the
# capillary number Ca = μ ū / G and the capillary's diameter. Each point is
# prm/deformation_map.prm (the default parachute, DM and DL at five
# instants) with, set on the command line:
# - Geometry/Capillary radius (Immersed cells/Squeeze into lumen where the
#   lumen is narrower than the cell),
# - Fluid/Inlet mean speed ū (and the frame's starting velocity 1.3 ū),
# - Membrane/Shear modulus G,
# - Time/Time step: 3e-4 s × min(1, 500 µm/s / ū), so that the cell moves as
#   far per step as in the default run, and 5e-5 s where the cell is
#   squeezed (the default step stops a squeezed run),
# - Time/Number of steps: 15 ms, 30 ms for a squeezed cell, which takes
#   longer to settle. A run the displacement guard stops (Immersed cells/Maximum
#   step displacement) is run again at half the step, up to three times;
#   the table gives the step that ran.
# POINTS is a file of lines "DIAMETER SPEED SHEAR_MODULUS" (µm, µm/s,
# pN/µm); the default is the map of doc/physiology.md: diameters 6-10 µm at
# (0.5 mm/s, 5.5 pN/µm) and at (2 mm/s, 2.5 pN/µm), and speeds 0.3-2 mm/s
# against G = 2.5, 5.5 and 10 pN/µm in the 10 µm capillary.
#
# Writes each run to output/deformation_map/D<diameter>_U<speed>_G<G>/ and
# the map to output/deformation_map/deformation_map.csv:
#   diameter [µm], mean_speed [µm/s], shear_modulus [pN/µm],
#   capillary_number, time_step [s], dm_start, dm_end, dl_start, dl_end
#   [µm³ s⁻¹ Torr⁻¹] (at t = 0, after any squeeze, and at the end),
#   dm_change, dl_change (end over start - 1), dm_last_change,
#   dl_last_change (the change over the last fifth of the run, over start:
#   how far from steady the shape still is), duration [s],
#   deformation_index, cell_speed [µm/s] (the frame's, at the end),
#   wall_gap [µm], seconds (the run's wall time).
# RBC_IFEM defaults to build/rbc-ifem, RANKS to 1. About 45 minutes on two
# ranks.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
exe=$(realpath "${1:-$here/build/rbc-ifem}")
ranks=${2:-1}
points=${3:-}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
prm=$here/prm/deformation_map.prm
out=output/deformation_map
mkdir -p "$out"

default_points() {
  for g in 2.5 5.5 10; do
    for u in 300 500 1000 2000; do echo "10 $u $g"; done
  done
  for d in 9 8 7 6; do echo "$d 500 5.5"; echo "$d 2000 2.5"; done
}

# column FILE NAME ROW: the value of column NAME in data row ROW of CSV FILE
# (ROW counts from 1; "last" for the last row).
column() {
  awk -F, -v name="$2" -v row="$3" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next }
    { v[NR - 1] = $c; n = NR - 1 } END { print (row == "last" ? v[n] : v[row]) }' "$1"
}

csv=$out/deformation_map.csv
echo "diameter,mean_speed,shear_modulus,capillary_number,time_step,dm_start,dm_end,dl_start,dl_end,dm_change,dl_change,dm_last_change,dl_last_change,duration,deformation_index,cell_speed,wall_gap,seconds" >"$csv"
while read -r diameter speed shear; do
  [ -n "$diameter" ] || continue
  dir=$out/D${diameter}_U${speed}_G${shear}
  radius=$(awk -v d="$diameter" 'BEGIN { print d / 2 }')
  squeeze=$(awk -v d="$diameter" 'BEGIN { print (d < 7.5 ? "true" : "false") }')
  dt=$(awk -v u="$speed" -v s="$squeeze" 'BEGIN { printf "%.6g", s == "true" ? 5e-5 : 3e-4 * (u > 500 ? 500 / u : 1) }')
  duration=$(awk -v s="$squeeze" 'BEGIN { print s == "true" ? 0.03 : 0.015 }')
  ran=false
  for attempt in 1 2 3 4; do
    steps=$(awk -v dt="$dt" -v T="$duration" 'BEGIN { printf "%d", T / dt / 5 + 0.5 }')
    steps=$((5 * steps))
    start=$(date +%s.%N)
    if mpirun -np "$ranks" "$exe" "$prm" \
         --set "Output directory=$dir" \
         --set "Geometry/Capillary radius=$radius" \
         --set "Immersed cells/Squeeze into lumen=$squeeze" \
         --set "Fluid/Inlet mean speed=$speed" \
         --set "Fluid/Frame velocity=$(awk -v u="$speed" 'BEGIN { print 1.3 * u }')" \
         --set "Membrane/Shear modulus=$shear" \
         --set "Time/Time step=$dt" --set "Time/Number of steps=$steps" \
         --set "Time/Output interval=$((steps / 5))" \
         --set "Immersed cells/Diffusion interval=$((steps / 5))" \
         --set "Immersed cells/Progress interval=$((steps / 5))" >"$dir.log" 2>&1 </dev/null; then
      ran=true
      break
    fi
    grep -q "Maximum step displacement" "$dir.log" || break
    dt=$(awk -v dt="$dt" 'BEGIN { printf "%.6g", dt / 2 }')
  done
  seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.0f", e - s }')
  if [ "$ran" != true ]; then
    echo "deformation_map: D = $diameter µm, ū = $speed µm/s, G = $shear pN/µm did not run (see $dir.log)" >&2
    continue
  fi
  dm=$dir/dm.csv
  cells=$dir/cells.csv
  dm0=$(column "$dm" dm_total 1); dm4=$(column "$dm" dm_total 5); dm5=$(column "$dm" dm_total last)
  dl0=$(column "$dm" dl_total 1); dl4=$(column "$dm" dl_total 5); dl5=$(column "$dm" dl_total last)
  awk -v D="$diameter" -v U="$speed" -v G="$shear" -v dt="$dt" \
      -v dm0="$dm0" -v dm4="$dm4" -v dm5="$dm5" -v dl0="$dl0" -v dl4="$dl4" -v dl5="$dl5" -v T="$duration" \
      -v di="$(column "$cells" deformation_index last)" -v gap="$(column "$cells" wall_gap last)" \
      -v v="$(column "$dir/flow.csv" frame_velocity last)" -v s="$seconds" \
      'BEGIN { printf "%s,%s,%s,%.4f,%s,%.6f,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f,%s,%.4f,%.1f,%.4f,%s\n",
                D, U, G, 1.2e-3 * U / G, dt, dm0, dm5, dl0, dl5, dm5 / dm0 - 1, dl5 / dl0 - 1,
                (dm5 - dm4) / dm0, (dl5 - dl4) / dl0, T, di, v, gap, s }' >>"$csv"
  tail -1 "$csv"
done < <(if [ -n "$points" ]; then cat "$points"; else default_points; fi)
echo "wrote $csv"

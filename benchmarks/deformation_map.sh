#!/usr/bin/env bash
# Usage: benchmarks/deformation_map.sh [RBC_IFEM] [RANKS] [POINTS]
#
# The deformation and confinement map (doc/physiology.md): how much of its
# CO uptake one red cell of 7.5 µm loses as the flow deforms it, against the
# capillary number Ca = μ ū / G and the capillary's diameter. Each point is
# prm/deformation_map.prm (the default parachute with DM and DL) with, set
# on the command line:
# - Geometry/Capillary radius (Immersed cells/Squeeze into lumen where the
#   lumen is narrower than the cell),
# - Fluid/Inlet mean speed ū (and the frame's starting velocity 1.3 ū),
# - Membrane/Shear modulus G,
# - Time/Time step: 3e-4 s × min(1, 500 µm/s / ū), so that the cell moves as
#   far per step as in the default run, and 5e-5 s where the cell is
#   squeezed (the default step stops a squeezed run),
# - Time/Number of steps: DM and DL every 3 ms; at least 15 ms, then on
#   from the last checkpoint (Immersed cells/Resume) 3 ms at a time until DM
#   changes by less than 0.1% of DM(0) over 3 ms (the shape is steady), or
#   until 60 ms. A run the displacement guard stops (Immersed
#   cells/Maximum step displacement) is run again from the start at half the
#   step, up to three times; the table gives the step that ran.
# POINTS is a file of lines "DIAMETER SPEED SHEAR_MODULUS" (µm, µm/s,
# pN/µm); the default is the map of doc/physiology.md: diameters 6-10 µm at
# (0.5 mm/s, 5.5 pN/µm) and at (2 mm/s, 2.5 pN/µm), and speeds 0.3-2 mm/s
# against G = 2.5, 5.5 and 10 pN/µm in the 10 µm capillary.
#
# Writes each run to output/deformation_map/D<diameter>_U<speed>_G<G>/ and
# the map to output/deformation_map/deformation_map.csv, and when it is
# done copies the map to doc/results/deformation_map/deformation_map.csv
# (RBC_IFEM_RESULTS/deformation_map.csv if that is set; benchmarks/common.sh):
#   commit, date, source (the run's, doc/results/README.md),
#   diameter [µm], mean_speed [µm/s], shear_modulus [pN/µm],
#   capillary_number, time_step [s], dm_start, dm_end, dl_start, dl_end
#   [µm³ s⁻¹ Torr⁻¹] (at t = 0, after any squeeze, and at the end),
#   dm_change, dl_change (end over start - 1), dm_last_change,
#   dl_last_change (the change over the last 3 ms, over start: how far from
#   steady the shape still is), duration [s], deformation_index, cell_speed
#   [µm/s] (the frame's, at the end), wall_gap [µm], seconds (the run's wall
#   time), steady (true if DM settled before 60 ms).
# RBC_IFEM defaults to build/rbc-ifem, RANKS to 1. About 80 minutes on two
# ranks.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
exe=$(realpath "${1:-$here/build/rbc-ifem}")
ranks=${2:-1}
points=${3:-}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
prm=$here/prm/deformation_map.prm
out=output/deformation_map
mkdir -p "$out"
# DM and DL every interval_time; a run lasts at least min_duration and then
# goes on an interval at a time until DM changes by less than tolerance (of
# DM(0)) over one interval, or until max_duration.
interval_time=0.003
min_duration=0.015
max_duration=0.06
tolerance=0.001

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
echo "commit,date,source,diameter,mean_speed,shear_modulus,capillary_number,time_step,dm_start,dm_end,dl_start,dl_end,dm_change,dl_change,dm_last_change,dl_last_change,duration,deformation_index,cell_speed,wall_gap,seconds,steady" >"$csv"

# run_to STEPS RESUME: run the point's prm file (the variables below) up to
# STEPS steps, from its last checkpoint if RESUME is true; the log appends.
run_to() {
  mpirun -np "$ranks" "$exe" "$prm" \
    --set "Output directory=$dir" \
    --set "Geometry/Capillary radius=$radius" \
    --set "Immersed cells/Squeeze into lumen=$squeeze" \
    --set "Fluid/Inlet mean speed=$speed" \
    --set "Fluid/Frame velocity=$(awk -v u="$speed" 'BEGIN { print 1.3 * u }')" \
    --set "Membrane/Shear modulus=$shear" \
    --set "Time/Time step=$dt" --set "Time/Number of steps=$1" \
    --set "Time/Output interval=$interval" \
    --set "Immersed cells/Diffusion interval=$interval" \
    --set "Immersed cells/Progress interval=$interval" \
    --set "Immersed cells/Checkpoint interval=$interval" \
    --set "Immersed cells/Resume=$2" >>"$dir.log" 2>&1 </dev/null
}

# last_change FILE NAME: the change of column NAME of dm.csv FILE between its
# last two rows, over its first row.
last_change() {
  awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next }
    NR == 2 { first = $c } { previous = last; last = $c } END { printf "%.6f", (last - previous) / first }' "$1"
}

while read -r diameter speed shear; do
  [ -n "$diameter" ] || continue
  dir=$out/D${diameter}_U${speed}_G${shear}
  radius=$(awk -v d="$diameter" 'BEGIN { print d / 2 }')
  squeeze=$(awk -v d="$diameter" 'BEGIN { print (d < 7.5 ? "true" : "false") }')
  dt=$(awk -v u="$speed" -v s="$squeeze" 'BEGIN { printf "%.6g", s == "true" ? 5e-5 : 3e-4 * (u > 500 ? 500 / u : 1) }')
  ran=false
  steady=false
  start=$(date +%s.%N)
  for attempt in 1 2 3 4; do
    interval=$(awk -v dt="$dt" -v T="$interval_time" 'BEGIN { printf "%d", T / dt + 0.5 }')
    steps=$(awk -v dt="$dt" -v T="$min_duration" -v n="$interval" 'BEGIN { printf "%d", n * int(T / dt / n + 0.5) }')
    : >"$dir.log"
    if run_to "$steps" false; then
      ran=true
      # Longer, an interval at a time, until DM settles or the longest run.
      while :; do
        change=$(last_change "$dir/dm.csv" dm_total)
        if awk -v c="$change" -v t="$tolerance" 'BEGIN { exit !(c < t && -c < t) }'; then
          steady=true
          break
        fi
        awk -v n="$steps" -v dt="$dt" -v T="$max_duration" 'BEGIN { exit !(n * dt < T - dt / 2) }' || break
        steps=$((steps + interval))
        run_to "$steps" true || { ran=false; break; }
      done
      [ "$ran" = true ] && break
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
  awk -v D="$diameter" -v U="$speed" -v G="$shear" -v dt="$dt" -v T="$(column "$dm" time last)" \
      -v dm0="$(column "$dm" dm_total 1)" -v dm5="$(column "$dm" dm_total last)" \
      -v dl0="$(column "$dm" dl_total 1)" -v dl5="$(column "$dm" dl_total last)" \
      -v ddm="$(last_change "$dm" dm_total)" -v ddl="$(last_change "$dm" dl_total)" \
      -v di="$(column "$cells" deformation_index last)" -v gap="$(column "$cells" wall_gap last)" \
      -v v="$(column "$dir/flow.csv" frame_velocity last)" -v s="$seconds" -v steady="$steady" \
      -v provenance="$(csv_field "$results_commit"),$(csv_field "$results_date"),$(csv_field "$results_source")" \
      'BEGIN { printf "%s,%s,%s,%s,%.4f,%s,%.6f,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f,%.4g,%.4f,%.1f,%.4f,%s,%s\n",
                provenance, D, U, G, 1.2e-3 * U / G, dt, dm0, dm5, dl0, dl5, dm5 / dm0 - 1, dl5 / dl0 - 1,
                ddm, ddl, T, di, v, gap, s, steady }' >>"$csv"
  tail -1 "$csv"
done < <(if [ -n "$points" ]; then cat "$points"; else default_points; fi)
stored=${RBC_IFEM_RESULTS:-$here/doc/results/deformation_map}
mkdir -p "$stored"
cp "$csv" "$stored/deformation_map.csv"
echo "wrote $csv and $stored/deformation_map.csv"

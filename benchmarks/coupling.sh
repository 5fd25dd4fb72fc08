#!/bin/bash
# The semi-implicit coupling against the explicit one on the default
# parachute (prm/default.prm), side by side in one run of this script:
#
#   bash benchmarks/coupling.sh [path/to/rbc-ifem] [ranks, default 2]
#
# - explicit: the paper's scheme at Δt = 1.5e-5 s (0.71 of its stability
#   estimate), 800 steps;
# - semi-implicit: prm/default.prm as it is, Δt = 3e-4 s (14 times the
#   estimate), 40 steps; and at 6e-4 and 1.5e-4 s for the time-step study;
# - with the area dilation modulus K = 500 pN/µm (the stretching
#   experiment's): semi-implicit at Δt = 4e-5 s and 1.2e-4 s, 17 and 52
#   times its explicit limit (300 and 100 steps), and explicit at 1.6e-6 s,
#   0.69 of it, 7500 steps.
#
# Prints the wall time of each whole run (DM solves included) and the ratios
# (at K = 50 and at K = 500), DM at every DM instant with the difference,
# the deformation index and the volume and area changes at 12 ms, the
# FGMRES iterations per step, the deformation index at 12 ms for Δt, Δt/2,
# Δt/4 with the observed order, the same comparison at K = 500 pN/µm, and
# the largest local area change (max over membrane cells of |A/A0 - 1|,
# cells.csv's local_area_change) at every DM instant at K = 50 and 500
# pN/µm. Each table's rows are added to doc/results/benchmarks/coupling_*.csv
# (benchmarks/common.sh). About 10 minutes on 2 ranks.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
benchmark_setup "${1:-}" "${2:-2}"

# run NAME COUPLING STEP STEPS DIFFUSION_INTERVAL [K]: a copy of the
# default run (with the area dilation modulus K [pN/µm]).
run() {
  local name=$1 coupling=$2 step=$3 steps=$4 interval=$5 modulus=${6:-50}
  { cat "$here/prm/default.prm"
    cat <<PRM
set Output directory = $name
subsection Membrane
  set Area dilation modulus = $modulus
end
subsection Time
  set Time step       = $step
  set Number of steps = $steps
  set Output interval = $interval
end
subsection Immersed cells
  set Coupling                  = $coupling
  set Diffusion interval        = $interval
  set Progress interval         = $interval
  set Checkpoint interval       = 0
  set Maximum step displacement = 1
end
PRM
  } > "$name.prm"
  local start end
  start=$(date +%s.%N)
  mpirun -np "$ranks" "$exe" "$name.prm" > "$name.log"
  end=$(date +%s.%N)
  echo "$end - $start" | bc > "$name.seconds"
}

run explicit explicit 1.5e-5 800 80
run semi semi-implicit 3e-4 40 4
run semi_coarse semi-implicit 6e-4 20 2
run semi_fine semi-implicit 1.5e-4 80 8
run semi_stiff semi-implicit 4e-5 300 30 500
run semi_stiff_large semi-implicit 1.2e-4 100 10 500
run explicit_stiff explicit 1.6e-6 7500 750 500

seconds() { printf '%.1f' "$(cat "$1.seconds")"; }
ratio() { echo "$(cat "$1.seconds") / $(cat "$2.seconds")" | bc -l | xargs printf '%.2f'; }
shape() { awk -F, -v c="$2" 'END { print $c }' "$1/cells.csv"; }
# row COMMAND...: the words COMMAND prints (an underscore in a word for a
# space), one row of the current table.
row() { local -a words; read -r -a words < <("$@"); results_row "$ranks" "${words[@]//_/ }"; }

echo "## Wall time of the whole default run on $ranks rank(s), DM solves included"
echo
results_table coupling_wall ranks "K [pN/µm]" coupling "Δt [s]" steps "wall [s]" "FGMRES iterations per step"
for name in explicit semi_fine semi semi_coarse explicit_stiff semi_stiff semi_stiff_large; do
  step=$(sed -n 's/^  set Time step *= *//p' "$name.prm" | tail -1)
  steps=$(sed -n 's/^  set Number of steps *= *//p' "$name.prm" | tail -1)
  modulus=$(sed -n 's/^  set Area dilation modulus *= *//p' "$name.prm" | tail -1)
  iterations=$(awk -F, 'NR > 1 { s += $8; n++ } END { printf "%.1f", s / n }' "$name/flow.csv")
  results_row "$ranks" "$modulus" "$(sed -n 's/^  set Coupling *= *//p' "$name.prm" | tail -1)" "$step" "$steps" \
    "$(seconds "$name")" "$iterations"
done
echo
results_table coupling_ratio ranks "K [pN/µm]" "explicit run" "over the semi-implicit run at Δt [s]" ratio
results_row "$ranks" 50 "1.5e-5 s, 800 steps" 3e-4 "$(ratio explicit semi)"
results_row "$ranks" 500 "1.6e-6 s, 7500 steps" 4e-5 "$(ratio explicit_stiff semi_stiff)"
results_row "$ranks" 500 "1.6e-6 s, 7500 steps" 1.2e-4 "$(ratio explicit_stiff semi_stiff_large)"
echo
echo "## DM at every DM instant [µm³/(s Torr)]"
echo
results_table coupling_dm ranks "t [ms]" "explicit 1.5e-5 s" "semi-implicit 3e-4 s" difference
paste -d, explicit/dm.csv semi/dm.csv | awk -F, 'NR > 1 { n = NF / 2
  printf "%.1f %.5f %.5f %+.3f%%\n", 1000 * $1, $2, $(n + 2), 100 * ($(n + 2) / $2 - 1) }' |
  while read -r -a words; do results_row "$ranks" "${words[@]}"; done
echo
echo "## The cell at 12 ms"
echo
results_table coupling_shape ranks "at 12 ms" "explicit 1.5e-5 s" "semi-implicit 3e-4 s" difference
a=$(shape explicit 10) b=$(shape semi 10)
results_row "$ranks" "deformation index" "$(printf '%.6f' "$a")" "$(printf '%.6f' "$b")" \
  "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%+.2e (%+.2f%%)", b - a, 100 * (b - a) / (a < 0 ? -a : a) }')"
a=$(shape explicit 12) b=$(shape semi 12)
results_row "$ranks" "volume change" "$(awk -v a="$a" 'BEGIN { printf "%+.4f%%", 100 * a }')" \
  "$(awk -v b="$b" 'BEGIN { printf "%+.4f%%", 100 * b }')" \
  "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%+.4f%% of the volume", 100 * (b - a) }')"
a=$(shape explicit 13) b=$(shape semi 13)
results_row "$ranks" "area change" "$(awk -v a="$a" 'BEGIN { printf "%+.4f%%", 100 * a }')" \
  "$(awk -v b="$b" 'BEGIN { printf "%+.4f%%", 100 * b }')" \
  "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%+.4f%% of the area", 100 * (b - a) }')"
echo
echo "## Time-step convergence of the semi-implicit coupling"
echo
d1=$(shape semi_coarse 10); d2=$(shape semi 10); d3=$(shape semi_fine 10); e=$(shape explicit 10)
results_table coupling_time_step ranks "Δt [s]" "deformation index at 12 ms" "change from the next larger Δt"
results_row "$ranks" 6e-4 "$(printf '%.6f' "$d1")" ""
results_row "$ranks" 3e-4 "$(printf '%.6f' "$d2")" "$(awk -v a="$d1" -v b="$d2" 'BEGIN { printf "%.2e", b - a }')"
results_row "$ranks" 1.5e-4 "$(printf '%.6f' "$d3")" "$(awk -v b="$d2" -v c="$d3" 'BEGIN { printf "%.2e", c - b }')"
echo
results_table coupling_order ranks "observed order (6e-4, 3e-4, 1.5e-4 s)" "deformation index at 12 ms, explicit 1.5e-5 s"
results_row "$ranks" "$(awk -v a="$d1" -v b="$d2" -v c="$d3" 'BEGIN { printf "%.2f", log((b - a) / (c - b)) / log(2) }')" \
  "$(printf '%.6f' "$e")"
echo
echo "## K = 500 pN/µm: explicit and semi-implicit"
echo
last_dm() { awk -F, 'END { print $2 }' "$1/dm.csv"; }
results_table coupling_stiff ranks "at 12 ms" "explicit 1.6e-6 s" "semi-implicit 4e-5 s" "semi-implicit 1.2e-4 s"
row awk -v a="$(last_dm explicit_stiff)" -v b="$(last_dm semi_stiff)" -v c="$(last_dm semi_stiff_large)" 'BEGIN {
  printf "DM_[µm³/(s_Torr)] %.5f %.5f_(%+.3f%%) %.5f_(%+.3f%%)\n", a, b, 100 * (b / a - 1), c, 100 * (c / a - 1) }'
row awk -v a="$(shape explicit_stiff 10)" -v b="$(shape semi_stiff 10)" -v c="$(shape semi_stiff_large 10)" 'BEGIN {
  printf "deformation_index %.6f %.6f_(%+.2f%%) %.6f_(%+.2f%%)\n", a, b, 100 * (b - a) / -a, c, 100 * (c - a) / -a }'
row awk -v a="$(shape explicit_stiff 12)" -v b="$(shape semi_stiff 12)" -v c="$(shape semi_stiff_large 12)" 'BEGIN {
  printf "volume_change %+.4f%% %+.4f%% %+.4f%%\n", 100 * a, 100 * b, 100 * c }'
echo
echo "## The largest local area change, max over membrane cells of |A/A0 - 1|, at every DM instant"
echo
results_table coupling_local_area_change ranks "t [ms]" "K = 50, semi-implicit 3e-4 s" "K = 500, explicit 1.6e-6 s" \
  "K = 500, semi-implicit 4e-5 s" "K = 500, semi-implicit 1.2e-4 s"
# column RUN NAME: the column NAME of RUN's cells.csv, without its header.
column() { awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i; next } { print $c }' "$1/cells.csv"; }
paste -d, <(column semi time) <(column semi local_area_change) <(column explicit_stiff local_area_change) \
  <(column semi_stiff local_area_change) <(column semi_stiff_large local_area_change) |
  awk -F, '{ printf "%.1f %.3f%% %.3f%% %.3f%% %.3f%%\n", 1000 * $1, 100 * $2, 100 * $3, 100 * $4, 100 * $5 }' |
  while read -r -a words; do results_row "$ranks" "${words[@]}"; done

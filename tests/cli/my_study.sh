#!/usr/bin/env bash
# Usage: my_study.sh [-n RANKS -m MPIEXEC] RBC_IFEM SOURCE_DIR PYTHON3
#
# The template study of doc/your_study.md: prm/my_study.prm and its layout
# prm/my_study_layout.csv, copied side by side into a scratch folder (so the
# layout file is found whether Layout/File is read from the working folder
# or from the parameter file's), run shortened to 2 steps of 3e-4 s with a
# DM solve at t = 0 and at the end and an output at each step. Checks the
# tables against the layout and against what DM can be, then draws the run
# with doc/scripts/plot_run.py (with --time) and checks the picture, and
# that plot_run.py refuses a --time outside the run and a folder that is not
# a flowing run, naming the file. Every number it checks is printed.
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
source_dir=$(realpath "$2")
python=$3
set_launcher "$ranks" "$mpiexec"
enter_scratch_directory

cp "$source_dir/prm/my_study.prm" "$source_dir/prm/my_study_layout.csv" . || exit 1
out=output/my_study
"${launcher[@]}" "$exe" my_study.prm \
  --set "Time/Number of steps=2" --set "Time/Output interval=1" \
  --set "Immersed cells/Diffusion interval=2" --set "Immersed cells/Progress interval=1" \
  >run.log 2>&1
status=$?
if [ $status -ne 0 ]; then
  cat run.log
  echo "FAILED: the shortened template exits with status $status"
  exit 1
fi
grep -E "^  (summary|DM at)" run.log

# cells.csv: the three cells of the layout at each of the 3 output times.
cells=$out/cells.csv
header=$(head -1 $cells)
for column in time cell x y min_gap wall_gap deformation_index volume_change area_change; do
  echo ",$header," | grep -q ",$column," || fail "$cells has no column $column: $header"
done
col() { # the number of column $1 of cells.csv
  echo "$header" | tr , '\n' | grep -n -x "$1" | cut -d: -f1
}
per_time=$(awk -F, 'NR > 1 { n[$1]++; c[$1] = c[$1] " " $2 }
                    END { for (t in n) print t ":" c[t] }' $cells | sort -g)
echo "cells.csv, the cells at each time:"
echo "$per_time" | sed 's/^/  t = /'
[ "$(echo "$per_time" | wc -l)" -eq 3 ] || fail "$cells: $(echo "$per_time" | wc -l) output times, not 3 (t = 0 and 2 steps)"
echo "$per_time" | grep -v -q ': 0 1 2$' && fail "$cells: a time without exactly the cells 0 1 2"

# The layout as read: the pair's gap and the third cell's wall gap at t = 0
# (the file's cells: the surfaces of cells 0 and 1 are 0.5406 µm apart,
# the run's "clearance" line; cell 2, 0.6 µm off the axis, is 5 - 3.75 - 0.6
# = 0.65 µm from the wall). The membrane mesh's nodes lie on the exact
# surface, so its gaps differ from the exact ones by far less than 0.02 µm;
# a layout not read from the file (uniform cells 5 µm apart) is off by µm.
at_start() { # cell column: the value at t = 0
  awk -F, -v c="$1" -v k="$(col "$2")" 'NR > 1 && $1 == 0 && $2 == c { print $k }' $cells
}
near() { # what value expected tolerance
  if awk -v v="$2" -v e="$3" -v t="$4" 'BEGIN { d = v - e; exit !(v != "" && (d < 0 ? -d : d) <= t) }'; then
    echo "ok: $1 = $2 (expected $3 ± $4)"
  else
    fail "$1 = '$2', expected $3 ± $4"
  fi
}
near "min_gap of cell 0 at t = 0 [µm]" "$(at_start 0 min_gap)" 0.5406 0.02
near "min_gap of cell 1 at t = 0 [µm]" "$(at_start 1 min_gap)" 0.5406 0.02
near "wall_gap of cell 2 at t = 0 [µm]" "$(at_start 2 wall_gap)" 0.65 0.02
# The volume penalty holds a stable run's volume within about 1%
# (Immersed cells/Maximum volume change); over 12 ms the template's cells
# stay within 0.06%.
largest=$(awk -F, -v k="$(col volume_change)" 'NR > 1 { v = $k < 0 ? -$k : $k; if (v > m) m = v }
                                              END { printf "%.3g", m }' $cells)
near "largest |volume_change|" "$largest" 0 0.01

# dm.csv: two solves of the three cells.
dm=$out/dm.csv
[ "$(head -1 $dm)" = "time,dm_total,dm_cell_0,dm_cell_1,dm_cell_2" ] || fail "$dm header: $(head -1 $dm)"
[ "$(($(wc -l < $dm) - 1))" -eq 2 ] || fail "$dm has $(($(wc -l < $dm) - 1)) rows, not 2 (t = 0 and step 2)"
# DM total is the sum of the cells' (each printed to ten digits: the sum
# is off by 1e-9 of it at most). Each cell's DM lies below a lone cell's
# in this segment, 4.18 (doc/results/layouts.csv, uniform, 1 cell; a
# neighbour only takes CO from it), with 3% for the difference of the
# meshes; and above the 1.98 per cell of the densest train the program
# places (7 clustered cells 0.2 µm apart, the same file), our cells having
# at most one neighbour closer than 4 µm. The lone cell 2 takes up at least
# 10% more than either of the pair, which shield each other (27% and 36%
# in the template's run).
awk -F, 'NR > 1 {
    sum = $3 + $4 + $5
    relative = ($2 - sum) / $2; if (relative < 0) relative = -relative
    printf "t = %s s: dm_total %s, cells %s %s %s, (total - sum)/total %.2g\n", $1, $2, $3, $4, $5, relative
    if (relative > 1e-8) { print "FAILED: dm_total is not the sum of the cells at t = " $1; bad = 1 }
    for (c = 3; c <= 5; ++c)
      if (!($c > 2.0 && $c < 4.3)) { print "FAILED: dm_cell_" c - 3 " = " $c " outside (2.0, 4.3)"; bad = 1 }
    if (!($5 > 1.1 * $3 && $5 > 1.1 * $4)) { print "FAILED: the lone cell 2 does not take up 10% more than cells 0 and 1"; bad = 1 }
  }
  END { exit bad }' $dm || failed=1
# DM at t = 0 is the rigid layout's: 9.7407 in the template's run. 1% is
# five times the uptake mesh's own error (0.05-0.19%, doc/diffusion.md),
# and less than what a layout misread would move (uniform cells: 10.55).
near "dm_total at t = 0 [µm³ s⁻¹ Torr⁻¹]" "$(awk -F, 'NR == 2 { print $2 }' $dm)" 9.7407 0.097
[ -s $out/checkpoint.bin ] || fail "no $out/checkpoint.bin"
for c in 0 1 2; do
  [ -s $out/cell_$c.pvd ] || fail "no $out/cell_$c.pvd"
done

# The picture, with the membranes at the last time.
plot=$source_dir/doc/scripts/plot_run.py
end=$(awk -F, 'END { print $1 }' $dm)
"$python" "$plot" $out --time "$end" --save run.png >plot.log 2>&1
status=$?
cat plot.log
if [ $status -eq 0 ]; then
  size=$(stat -c %s run.png 2>/dev/null || echo 0)
  [ "$size" -gt 10000 ] && [ "$(head -c 4 run.png | tail -c 3)" = PNG ] \
    && echo "ok: run.png, $size bytes" || fail "run.png is missing, empty or not a PNG ($size bytes)"
else
  fail "plot_run.py $out --time $end exits with status $status"
fi
# Refused, with the file named: a time after the run's end, and a folder of
# another experiment (the run's own output/ holds no cells.csv).
"$python" "$plot" $out --time 1 --save late.png >late.log 2>&1 && fail "plot_run.py accepts --time 1 s, after the run's end"
grep -q "outside the run.*$out/cell_0.pvd" late.log && echo "ok: $(cat late.log)" \
  || fail "plot_run.py --time 1: $(cat late.log)"
[ -e late.png ] && fail "plot_run.py --time 1 wrote late.png"
"$python" "$plot" output --save none.png >none.log 2>&1 && fail "plot_run.py accepts output/, not a run"
grep -q "output/cells.csv does not exist" none.log && echo "ok: $(cat none.log)" \
  || fail "plot_run.py output: $(cat none.log)"

[ $failed -eq 0 ] && echo "ok: the template study runs and plots"
exit $failed

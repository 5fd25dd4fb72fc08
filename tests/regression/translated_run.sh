#!/usr/bin/env bash
# Usage: translated_run.sh [-n RANKS -m MPIEXEC] RBC_IFEM PRM SHIFT NUMDIFF [DM_TOLERANCE]
#
# Runs a flowing experiment of a periodic segment twice: as PRM says, and
# with the cells starting SHIFT µm further along x: Layout/Cluster position
# changed (set in PRM as "Cluster position = A" and written by the test as
# A + SHIFT/L), or with Layout/Kind = file every x of the layout file (named
# relative to PRM's folder) moved by SHIFT. In a periodic segment whose meshes repeat with the
# shift, the two runs are the same run translated: cells.csv must agree in
# every column but the positions along x, which must differ by SHIFT (to
# 1e-6 µm), and
# dm.csv must agree, to solver tolerance (numdiff, relative DM_TOLERANCE,
# 1e-6 unless given). Used with a shift that carries the cells through the
# segment's end.
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
prm=$2
shift_x=$3
numdiff=$4
dm_tolerance=${5:-1e-6}

set_launcher "$ranks" "$mpiexec"
enter_scratch_directory

length=$(sed -n 's/^ *set Capillary length *= *//p' "$prm")
position=$(sed -n 's/^ *set Cluster position *= *//p' "$prm")
moved=$(awk -v p="$position" -v s="$shift_x" -v l="${length:-20}" 'BEGIN { printf "%.12g", p + s / l }')
sed -e "s/^\( *set Cluster position *=\).*/\1 $moved/" -e "s/^\(set Output directory *=\).*/\1 moved/" "$prm" >moved.prm
sed -e "s/^\(set Output directory *=\).*/\1 first/" "$prm" >first.prm
layout=$(sed -n 's/^ *set File *= *//p' "$prm")
if [ -n "$layout" ]; then
  # Both runs read their layout from here: the first as given, the moved one
  # with x + SHIFT.
  cp "$(dirname "$prm")/$layout" first_layout.csv
  awk -F, -v OFS=, -v s="$shift_x" 'NR > 1 { $1 = $1 + s } { print }' first_layout.csv >moved_layout.csv
  sed -i "s|^\( *set File *=\).*|\1 $PWD/first_layout.csv|" first.prm
  sed -i "s|^\( *set File *=\).*|\1 $PWD/moved_layout.csv|" moved.prm
fi

failed=0
for run in first moved; do
  "${launcher[@]}" "$exe" $run.prm >$run.log 2>&1 || { cat $run.log; echo "FAILED: the $run run"; exit 1; }
done
grep -E "DM|step" moved.log | tail -4

# cells.csv without x and frame_x; the shift of x on every row.
without_x() { cut -d, -f1,2,4-10,12- "$1"; }
without_x first/cells.csv >first_cells.csv
without_x moved/cells.csv >moved_cells.csv
for pair in "first_cells.csv moved_cells.csv 1e-6" "first/dm.csv moved/dm.csv $dm_tolerance"; do
  read -r a b tolerance <<<"$pair"
  if ! "$numdiff" -q -s ' \t\n,' -r "$tolerance" -a 1e-10 "$a" "$b"; then
    echo "FAILED: $b differs from $a:"
    "$numdiff" -s ' \t\n,' -r "$tolerance" -a 1e-10 "$a" "$b" | head -20
    failed=1
  fi
done
largest=$(paste -d, first/cells.csv moved/cells.csv | awk -F, -v n="$(head -1 first/cells.csv | awk -F, '{ print NF }')" -v s="$shift_x" '
  NR > 1 { d = $(n + 3) - $3 - s; if (d < 0) d = -d; if (d > m) m = d } END { printf "%.3g", m }')
echo "largest |x_moved - x_first - $shift_x| = $largest µm"
awk -v d="$largest" 'BEGIN { exit !(d <= 1e-6) }' || { echo "FAILED: the cells' x do not differ by the shift"; failed=1; }
awk -F, -v l="${length:-20}" 'NR > 1 { if ($3 + $8 / 2 > l) crossed = 1 } END { exit !crossed }' moved/cells.csv ||
  { echo "FAILED: the moved cells never reach the end of the segment"; failed=1; }
[ $failed -eq 0 ] && echo "ok: the moved run is the first one translated by $shift_x µm"
exit $failed

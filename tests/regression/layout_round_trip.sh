#!/usr/bin/env bash
# Usage: layout_round_trip.sh RBC_IFEM PRM NUMDIFF
#
# Layout/Kind = file reads back what a run wrote: PRM is a flowing layouts
# study of one layout (Output directory output/NAME); its run's own
# parameters.prm, with Layout/Kind = file and Layout/File the study's
# layout_<kind>_<n>_<seed>.csv, runs again and gives the same cells.csv and
# dm.csv (the positions come back to the file's ten digits; cells.csv less
# its inclination, which is ±π/2 at random for a cell seen end-on). Then the
# layout file with a word for a number is refused, naming the file, the
# line and the cell, with exit status 1 and nothing written.
set -u
source "$(dirname "$0")/../script_setup.sh"
exe=$1
prm=$2
numdiff=$3
enter_scratch_directory

"$exe" "$prm" >study.log 2>&1
status=$?
[ $status -eq 0 ] || { cat study.log; echo "FAILED: the study exits with status $status"; exit 1; }
study=$(sed -n 's/^set Output directory *= *//p' "$prm")
layout=$(cd "$study" && ls layout_*.csv)
run=${layout#layout_}
run=$study/${run%.csv}
echo "study run $run, layout $layout"

# The run's parameters.prm, writing elsewhere and reading its layout file.
rerun() {
  sed -e "s|^set Output directory *=.*|set Output directory = $2|" \
      -e "s|^  set Kind  *=.*|  set Kind = file|" \
      -e "s|^  set File  *=.*|  set File = $1|" "$run/parameters.prm" >"$3"
}
rerun "$study/$layout" from_file from_file.prm
"$exe" from_file.prm >from_file.log 2>&1
status=$?
[ $status -eq 0 ] || { cat from_file.log; echo "FAILED: the rerun exits with status $status"; exit 1; }
# CSV file $1 without its column inclination.
without_inclination() {
  awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "inclination") c = i }
                    { if (c) { for (i = c; i < NF; ++i) $i = $(i + 1); NF-- } print }' "$1"
}
failed=0
for table in cells.csv dm.csv; do
  without_inclination "$run/$table" >study_$table
  without_inclination "from_file/$table" >from_file_$table
  if "$numdiff" -q -s ' \t\n,' -r 1e-6 -a 1e-9 study_$table from_file_$table; then
    echo "ok: $table from the layout file matches the study's run"
  else
    echo "FAILED: $table from the layout file differs from the study's run:"
    "$numdiff" -s ' \t\n,' -r 1e-6 -a 1e-9 study_$table from_file_$table | head -20
    failed=1
  fi
done

sed '3s/^[^,]*,/one,/' "$study/$layout" >bad_layout.csv
rerun bad_layout.csv bad bad.prm
"$exe" bad.prm >bad.log 2>&1
status=$?
sed 's/^/  /' bad.log
[ $status -eq 1 ] || { echo "FAILED: a bad layout file exits with status $status, not 1"; failed=1; }
grep -qF "'Layout/File' = 'bad_layout.csv'" bad.log && grep -qF "line 3 (cell 1): 'one' is not a number" bad.log ||
  { echo "FAILED: the message does not name the file, the line and the cell"; failed=1; }
[ -e bad ] && { echo "FAILED: a bad layout file wrote output"; failed=1; }
[ $failed -eq 0 ] && echo "ok"
exit $failed

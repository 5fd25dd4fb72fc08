#!/usr/bin/env bash
# Usage: input_files.sh RBC_IFEM
#
# Input files named by parameters (doc/outputs.md, "Inputs"): a relative
# Layout/File is taken from the parameter file's folder, whatever the working
# directory; a --set one from the working directory; a missing one is refused
# with the path that was tried. The run copies the layout into
# OUTPUT/inputs/ and its parameters.prm names the copy, so that rerunning
# OUTPUT/parameters.prm gives the same cells even after the original file
# was edited.
set -u
exe=$1
source "$(dirname "$0")/../script_setup.sh"
enter_scratch_directory

mkdir -p study elsewhere
cat >study/three_cells.csv <<'CSV'
x,y,z,axis_x,axis_y,axis_z
5,0,0,1,0,0
10,0.5,0,1,0,0.2
15,0,0,1,0,0
CSV
cat >study/run.prm <<'PRM'
set Experiment = geometry
set Output directory = out/first
subsection Layout
  set Kind = file
  set File = three_cells.csv
end
PRM

# From another working directory, the prm by a relative path: the layout is
# found beside the prm.
(cd elsewhere && "$exe" ../study/run.prm >run.log 2>&1) || fail "run from elsewhere/: $(tail -2 elsewhere/run.log)"
first=elsewhere/out/first
[ "$(wc -l <$first/cells.csv)" -eq 4 ] || fail "cells.csv has $(($(wc -l <$first/cells.csv) - 1)) cells, not 3"
cmp -s study/three_cells.csv $first/inputs/three_cells.csv || fail "no copy of the layout in $first/inputs/"
grep -q "^ *set File *= inputs/three_cells.csv$" $first/parameters.prm || fail "parameters.prm does not name the copy: $(grep 'set File' $first/parameters.prm)"

# The original edited (a cell moved): the output's parameters.prm still
# reruns the run as it was, from its copy.
sed -i 's/^10,0.5,0,/11,0.5,0,/' study/three_cells.csv
"$exe" $first/parameters.prm --set "Output directory=again" >again.log 2>&1 || fail "rerun of parameters.prm: $(tail -2 again.log)"
cmp -s $first/cells.csv again/cells.csv || fail "the rerun's cells.csv differs: $(diff $first/cells.csv again/cells.csv)"
# The same file run in place reads its own copy and leaves it.
"$exe" $first/parameters.prm >in_place.log 2>&1 || fail "rerun in place: $(tail -2 in_place.log)"
cmp -s $first/cells.csv again/cells.csv || fail "the rerun in place changed cells.csv"
grep -q "^11,0.5" $first/inputs/three_cells.csv && fail "the rerun in place replaced its copy by the edited original"

# --set: relative to the working directory.
"$exe" study/run.prm --set "Layout/File=study/three_cells.csv" --set "Output directory=by_set" >set.log 2>&1 || fail "--set Layout/File: $(tail -2 set.log)"
grep -q "^1,11," by_set/cells.csv || fail "--set Layout/File did not read study/three_cells.csv: $(sed -n 3p by_set/cells.csv)"

# A missing file: exit 1, the path tried named, nothing written.
rm study/three_cells.csv
(cd elsewhere && "$exe" ../study/run.prm --set "Output directory=missing" >missing.log 2>&1)
status=$?
[ $status -eq 1 ] || fail "a missing layout: exit status $status, not 1"
grep -qF "no readable file $work/study/three_cells.csv" elsewhere/missing.log || fail "the message does not name the path tried: $(cat elsewhere/missing.log)"
[ -e elsewhere/missing ] && fail "a missing layout: the run wrote elsewhere/missing"

[ $failed -eq 0 ] && echo "input files: resolved, copied, rerun alike"
exit $failed

#!/usr/bin/env bash
# Usage: command_line.sh RBC_IFEM
#
# The program's command line (doc/design.md, Section 4): --help, --version, a
# run with no file (the usage), an unknown option, and --print-parameters,
# whose output must be a valid .prm that runs and give every parameter's
# allowed values; the parameters.prm a run writes must run again and give the
# same cells.csv; --set changes parameters, checked like the file, and
# parameters.prm records them; magnitudes outside 1e-15 to 1e15 are refused;
# a byte-order mark is read past, an entry set twice and an empty file warned
# about.
set -u
exe=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failed=0
fail() { echo "FAILED: $*"; failed=1; }

"$exe" --help >help.txt 2>&1 || fail "--help exits with status $?"
grep -q "Usage: rbc-ifem FILE.prm" help.txt || fail "--help prints no usage"

"$exe" --version >version.txt 2>&1 || fail "--version exits with status $?"
grep -q "^rbc-ifem [0-9][0-9.]* (git [0-9a-z-]*)$" version.txt || fail "--version prints '$(cat version.txt)'"

"$exe" >/dev/null 2>none.txt && fail "a run with no file exits with status 0"
grep -q "Usage: rbc-ifem FILE.prm" none.txt || fail "a run with no file prints no usage"
[ "$(wc -l < none.txt)" -lt 30 ] || fail "a run with no file prints $(wc -l < none.txt) lines, not the usage"

"$exe" --frobnicate >/dev/null 2>&1 && fail "an unknown option exits with status 0"

"$exe" --print-parameters >all.prm || fail "--print-parameters exits with status $?"
for name in "Capillary radius" "Capillary length" "Wall thickness" "Gas layer thickness" \
            "Diameter" "Kind" "Number of cells" "Seed" "Minimum gap" "Output directory"; do
  grep -q "set $name " all.prm || fail "--print-parameters lacks '$name'"
done

sets=$(grep -c '^ *set ' all.prm)
[ "$sets" -gt 80 ] && [ "$(grep -c '^ *# Allowed: ' all.prm)" -eq "$sets" ] \
  || fail "--print-parameters: $(grep -c '^ *# Allowed: ' all.prm) 'Allowed' lines for $sets parameters"
grep -q "# Allowed: one of geometry | diffusion | layouts" all.prm || fail "--print-parameters: Experiment's allowed values"
grep -q "# Allowed: a number ≥ 0$" all.prm || fail "--print-parameters: no 'a number ≥ 0'"
grep -q "# Allowed: a number > 0, or auto" all.prm || fail "--print-parameters: Time step's allowed values"
head -1 all.prm | grep -q "^# Listing of Parameters of rbc-ifem [0-9.]* (git " || fail "--print-parameters: first line $(head -1 all.prm)"

"$exe" all.prm >run1.txt 2>&1 || fail "the printed defaults do not run: $(cat run1.txt)"
out=output/run
for file in parameters.prm cells.csv timing.csv fluid_mesh.pvd diffusion_mesh.pvd \
            fluid_mesh_boundary.pvd diffusion_mesh_boundary.pvd membranes.pvd membranes.vtu; do
  [ -s "$out/$file" ] || fail "the default run wrote no $out/$file"
done
[ "$(head -1 $out/cells.csv)" = "cell,x,y,z,area,volume" ] || fail "cells.csv header: $(head -1 $out/cells.csv)"
[ "$(wc -l < $out/cells.csv)" -eq 5 ] || fail "cells.csv should have 4 cells"
[ "$(head -1 $out/timing.csv)" = "section,calls,wall_seconds" ] || fail "timing.csv header"
ls $out | grep -q '\.part$' && fail "temporary files left behind"

sed 's|^set Output directory.*|set Output directory = output/again|' $out/parameters.prm >again.prm
"$exe" again.prm >run2.txt 2>&1 || fail "the written parameters.prm does not run"
cmp -s $out/cells.csv output/again/cells.csv || fail "parameters.prm does not reproduce cells.csv"

# --set: two changes, recorded in parameters.prm, same as the file.
"$exe" all.prm --set "Output directory=output/set" --set "Layout/Number of cells = 2" >set.txt 2>&1 \
  || fail "a run with --set: $(tail -2 set.txt)"
[ "$(wc -l < output/set/cells.csv)" -eq 3 ] || fail "--set 'Layout/Number of cells = 2' gave $(($(wc -l < output/set/cells.csv) - 1)) cells"
grep -q "^  set Number of cells *= 2" output/set/parameters.prm || fail "parameters.prm does not record the --set"
bad_set() { # expected-words arguments...
  local words=$1
  shift
  rm -rf output/bad
  "$exe" all.prm --set "Output directory=output/bad" "$@" >bad.txt 2>&1
  local status=$?
  [ $status -eq 1 ] || fail "--set $*: exit status $status, not 1"
  grep -q "$words" bad.txt || fail "--set $*: the message lacks '$words': $(cat bad.txt)"
  [ -e output/bad ] && fail "--set $*: the run wrote output/bad"
  echo "ok: $* -> $(grep error bad.txt)"
}
bad_set "no parameter 'Layout/Number of cels'. Did you mean 'Layout/Number of cells'?" --set "Layout/Number of cels=2"
bad_set "no parameter 'Number of cells'. Did you mean 'Layout/Number of cells'?" --set "Number of cells=2"
bad_set "no parameter 'Capillary radius'. An entry 'Capillary radius' is in subsection 'Geometry'." --set "Capillary radius=2"
bad_set "parameter 'Layout/Number of cells' = '-2' is not allowed: a whole number ≥ 0" --set "Layout/Number of cells=-2"
bad_set "expected \"Subsection/Name=value\"" --set "Layout/Number of cells"
bad_set "parameter 'Geometry/Capillary radius' = '0'" --set "Geometry/Capillary radius=0"
"$exe" all.prm --set >/dev/null 2>&1 && fail "a --set without its value exits with status 0"
# Magnitudes no physical value here takes.
bad_set "parameter 'Fluid/Viscosity' = '1e308' is not allowed: a number of magnitude between 1e-15 and 1e15" \
  --set "Fluid/Viscosity=1e308"
bad_set "parameter 'Time/Time step' = '1e-300' is not allowed: a number of magnitude between 1e-15 and 1e15" \
  --set "Time/Time step=1e-300"
bad_set "parameter 'Geometry/Capillary radius' = '1e308'" --set "Geometry/Capillary radius=1e308"

# A file that starts with a UTF-8 byte-order mark runs; an entry set twice
# and a file that sets nothing run with a warning.
{ printf '\xEF\xBB\xBF'; sed 's|^set Output directory.*|set Output directory = output/bom|' all.prm; } >bom.prm
"$exe" bom.prm >bom.txt 2>&1 && [ -s output/bom/cells.csv ] || fail "a file with a byte-order mark: $(tail -2 bom.txt)"
{ cat all.prm; printf 'set Output directory = output/twice\nsubsection Layout\n  set Number of cells = 2\nend\n'; } >twice.prm
"$exe" twice.prm >twice.txt 2>&1 || fail "a file with an entry set twice: $(tail -2 twice.txt)"
grep -q "warning: twice.prm, line [0-9]*: Layout/Number of cells is set again (first on line [0-9]*); this later value, 2, is the one used" twice.txt \
  && echo "ok: $(grep warning twice.txt | grep 'Number of cells')" || fail "no warning for an entry set twice: $(head -3 twice.txt)"
: >empty.prm
"$exe" empty.prm --set "Output directory=output/empty" >empty.txt 2>&1 || fail "an empty file: $(tail -2 empty.txt)"
grep -q "warning: empty.prm sets no parameter" empty.txt && echo "ok: $(grep warning empty.txt)" \
  || fail "no warning for an empty file: $(head -2 empty.txt)"

[ $failed -eq 0 ] && echo "ok: command line, defaults, --set and parameters.prm round trip"
exit $failed

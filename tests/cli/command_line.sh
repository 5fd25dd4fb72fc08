#!/usr/bin/env bash
# Usage: command_line.sh RBC_IFEM
#
# The program's command line (doc/design.md, Section 4): --help, a run with no
# file, an unknown option, and --print-parameters, whose output must be a
# valid .prm that runs; the parameters.prm a run writes must run again and
# give the same cells.csv.
set -u
exe=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failed=0
fail() { echo "FAILED: $*"; failed=1; }

"$exe" --help >help.txt 2>&1 || fail "--help exits with status $?"
grep -q "Usage: rbc-ifem FILE.prm" help.txt || fail "--help prints no usage"

"$exe" >/dev/null 2>none.txt && fail "a run with no file exits with status 0"
grep -q "set Experiment" none.txt || fail "a run with no file does not list the parameters"

"$exe" --frobnicate >/dev/null 2>&1 && fail "an unknown option exits with status 0"

"$exe" --print-parameters >all.prm || fail "--print-parameters exits with status $?"
for name in "Capillary radius" "Capillary length" "Wall thickness" "Gas layer thickness" \
            "Diameter" "Kind" "Number of cells" "Seed" "Minimum gap" "Output directory"; do
  grep -q "set $name " all.prm || fail "--print-parameters lacks '$name'"
done

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

[ $failed -eq 0 ] && echo "ok: command line, defaults and parameters.prm round trip"
exit $failed

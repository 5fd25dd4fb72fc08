#!/usr/bin/env bash
# Usage: defaults.sh RBC_IFEM
#
# The program's defaults are its best settings (doc/design.md, Section 6): a
# parameter file with only Experiment = flow and Immersed cells/Enabled =
# true runs the semi-implicit coupling at its automatic step, and its uptake
# would be solved on cut cells of degree 2. Asserted from the run's
# parameters.prm (by subsection: several subsections have a Finite element
# degree) and its start-up line; one step keeps it short.
set -u
exe=$1
source "$(dirname "$0")/../script_setup.sh"
enter_scratch_directory

cat >only.prm <<'PRM'
set Experiment = flow
subsection Immersed cells
  set Enabled = true
end
PRM
"$exe" only.prm --set "Time/Number of steps=1" >run.log 2>&1 || fail "the run failed: $(tail -3 run.log)"

# value SUBSECTION NAME: the value of NAME in SUBSECTION of parameters.prm.
value() {
  awk -v sub_name="$1" -v name="$2" '
    /^ *subsection / { sub($1 FS, ""); section = $0 }
    /^ *end *$/ { section = "" }
    $1 == "set" && section == sub_name {
      line = $0; sub(/^ *set +/, "", line); split(line, kv, / *= */)
      if (kv[1] == name) print kv[2] }' output/run/parameters.prm
}
expect() {
  local found
  found=$(value "$1" "$2")
  [ "$found" = "$3" ] || fail "$1/$2 = '$found', not '$3'"
}
expect "Immersed cells" Coupling semi-implicit
expect Diffusion Method "cut cell"
expect Diffusion "Finite element degree" 2
expect Mesh "Diffusion band refinements" 1
expect Time "Time step" auto
grep -q "coupling semi-implicit, Δt = .* (Time step = auto, 10 of the estimate)" run.log ||
  fail "the start-up line does not report the automatic semi-implicit step: $(grep 'coupling ' run.log)"
exit $failed

#!/usr/bin/env bash
# Usage: reference_command_line.sh SPHERE_IN_TUBE_REFERENCE
#
# The reference program's command line: --help, a short run's CSV, and bad
# arguments rejected with the argument's name, the value and what is
# allowed, before any output.
set -u
exe=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failed=0
fail() { echo "FAILED: $*"; failed=1; }

"$exe" --help | grep -q "Usage: sphere-in-tube-reference" || fail "--help prints no usage"

"$exe" 0.5 1 > run.csv || fail "a run exits with status $?"
[ "$(head -1 run.csv)" = "lambda,refinements,cells,dofs,towed_drag_factor,held_drag_factor,velocity_ratio,wall_seconds" ] \
  || fail "header: $(head -1 run.csv)"
[ "$(wc -l < run.csv)" -eq 3 ] || fail "refinements 0 and 1 should give two rows"

# bad ARGUMENTS... EXPECTED: exits non-zero, prints nothing on standard
# output, and says EXPECTED on standard error.
bad() {
  local expected=${*: -1}
  "$exe" "${@:1:$#-1}" > out.txt 2> err.txt && fail "'${*:1:$#-1}' exits with status 0"
  [ -s out.txt ] && fail "'${*:1:$#-1}' wrote output"
  grep -qF "$expected" err.txt || fail "'${*:1:$#-1}' does not say '$expected': $(cat err.txt)"
}
bad 1.2 "LAMBDA"
bad 1.2 "(0, 0.9]"
bad 0.5x "a number"
bad 0.5 9 "REFINEMENTS"
bad 0.5 2.5 "an integer from 0 to 7"
bad 0.5 2 1 "HALF_LENGTH"
bad 0.5 2 4 7 "at most three arguments"
[ $failed -eq 0 ] && echo "all checks passed"
exit $failed

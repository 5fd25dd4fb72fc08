#!/usr/bin/env bash
# Usage: experiments.sh RBC_IFEM TESTS_DIR
#
# The experiment registry is the one list of experiment names: read it from
# the program (--list-experiments) and check that --print-parameters
# documents each, that every experiment has a stored-output test (a .prm
# under TESTS_DIR that sets it), and that an unknown name is an input error
# whose message offers exactly the registry's names, in its order.
set -u
exe=$1
tests=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failed=0
fail() { echo "FAILED: $*"; failed=1; }

"$exe" --list-experiments >names.txt || fail "--list-experiments exits with status $?"
mapfile -t names <names.txt
[ ${#names[@]} -gt 0 ] || fail "--list-experiments lists no experiment"
echo "registry: ${names[*]}"
selection=$(IFS='|'; echo "${names[*]}")

# The documentation of Experiment: the comment lines before its entry, joined.
"$exe" --print-parameters |
  awk '/^set Experiment/ { exit } /^# / { sub(/^# /, ""); printf "%s ", $0 }' >documentation.txt
for name in "${names[@]}"; do
  grep -qF "$name: " documentation.txt || fail "--print-parameters does not document '$name'"
  grep -rlqE "^ *set Experiment *= *$name *$" "$tests" --include='*.prm' ||
    fail "no test runs the experiment '$name'"
done

printf 'set Experiment = tank treading\n' >unknown.prm
"$exe" unknown.prm >/dev/null 2>unknown.txt
status=$?
[ $status -eq 1 ] || fail "an unknown experiment exits with status $status, not 1"
grep -qF "tank treading" unknown.txt || fail "the message does not name the value"
grep -qF "one of ${selection//|/ | }" unknown.txt || fail "the message does not list the registry's names"
[ -e output ] && fail "an unknown experiment wrote output"

[ $failed -eq 0 ] && echo "ok: ${#names[@]} experiments, each offered, documented and tested"
exit $failed

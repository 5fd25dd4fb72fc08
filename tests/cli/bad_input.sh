#!/usr/bin/env bash
# Usage: bad_input.sh RBC_IFEM PRM_FILE|MISSING EXPECTED_TEXT...
#
# Runs rbc-ifem on a bad parameter file (MISSING: on a file that does not
# exist) in an empty directory, and checks that it exits with status 1 (an
# input error, not a crash), that its message contains every EXPECTED_TEXT
# (the parameter, the value, what is allowed), and that it wrote nothing.
set -u
exe=$1
prm=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
touch clash  # a file where a test asks for an output directory
if [ "$prm" = MISSING ]; then
  input=does-not-exist.prm
else
  # Where it is: files it names (a layout) are found beside it.
  input=$prm
fi

"$exe" "$input" >stdout.txt 2>stderr.txt
status=$?
echo "exit status: $status"
echo "message:"
sed 's/^/  /' stderr.txt

failed=0
if [ "$status" -ne 1 ]; then
  echo "FAILED: expected exit status 1"
  failed=1
fi
for text in "$@"; do
  if ! grep -qF -- "$text" stderr.txt; then
    echo "FAILED: the message does not contain '$text'"
    failed=1
  fi
done
written=$(ls -A | grep -v -x -e input.prm -e stdout.txt -e stderr.txt -e clash)
if [ -n "$written" ]; then
  echo "FAILED: output was written: $written"
  failed=1
fi
[ $failed -eq 0 ] && echo "ok"
exit $failed

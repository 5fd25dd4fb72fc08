#!/usr/bin/env bash
# Usage: compare_run.sh RBC_IFEM PRM EXPECTED_DIR NUMDIFF [MPIEXEC N]
#
# Runs an experiment (on N MPI ranks if MPIEXEC is given) in an empty
# directory and compares its log and the CSV files stored in EXPECTED_DIR
# with numdiff (relative tolerance 1e-8, absolute 1e-10 for values near 0).
# The log lines naming the number of ranks and the memory used are left
# out of the comparison.
set -u
exe=$1
prm=$2
expected=$3
numdiff=$4
launcher=()
if [ $# -ge 6 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  launcher=("$5" -np "$6")
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

"${launcher[@]}" "$exe" "$prm" >log.txt 2>&1
status=$?
cat log.txt
[ $status -eq 0 ] || { echo "FAILED: exit status $status"; exit 1; }
grep -v -e "rank(s)" -e "peak memory" log.txt >run.log

directory=$(sed -n 's/^set Output directory *= *//p' "$prm")
failed=0
for reference in "$expected"/*; do
  name=$(basename "$reference")
  if [ "$name" = run.log ]; then result=run.log; else result="$directory/$name"; fi
  if ! "$numdiff" -q -r 1e-8 -a 1e-10 "$reference" "$result"; then
    echo "FAILED: $name differs from the stored $reference:"
    "$numdiff" -r 1e-8 -a 1e-10 "$reference" "$result" | head -20
    failed=1
  fi
done
[ $failed -eq 0 ] && echo "ok: matches $expected"
exit $failed

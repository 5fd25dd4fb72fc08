#!/usr/bin/env bash
# Usage: restart.sh [-n RANKS -m MPIEXEC] RBC_IFEM PRM NUMDIFF
#
# Checkpoint and restart of a flowing run: runs PRM for its 2n steps in one
# go, and again as n steps (writing a checkpoint) plus a resumed run to
# step 2n, and requires the tables of both to agree to 1e-12 (relative).
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
prm=$2
numdiff=$3

set_launcher "$ranks" "$mpiexec"
enter_scratch_directory

steps=$(sed -n 's/^ *set Number of steps *= *//p' "$prm")
half=$((steps / 2))
# PRM with the entries given here appended: a later entry wins.
variant() { # directory steps resume
  cat "$prm"
  printf 'set Output directory = %s\n' "$1"
  printf 'subsection Time\n  set Number of steps = %s\nend\n' "$2"
  printf 'subsection Immersed cells\n  set Checkpoint interval = %s\n  set Resume = %s\nend\n' "$half" "$3"
}
variant straight "$steps" false >straight.prm
variant restarted "$half" false >first_half.prm
variant restarted "$steps" true >second_half.prm

for run in straight first_half second_half; do
  echo "== $run"
  "${launcher[@]}" "$exe" $run.prm >$run.log 2>&1 || { cat $run.log; echo "FAILED: $run"; exit 1; }
  grep -e "resumed" -e "step $steps," $run.log
done

failed=0
for table in flow.csv cells.csv dm.csv; do
  if ! "$numdiff" -q -s ' \t\n,' -r 1e-12 -a 1e-14 straight/$table restarted/$table; then
    echo "FAILED: $table of the restarted run differs from the straight run:"
    "$numdiff" -s ' \t\n,' -r 1e-12 -a 1e-14 straight/$table restarted/$table | head -20
    failed=1
  elif cmp -s straight/$table restarted/$table; then
    echo "$table: identical"
  else
    echo "$table: equal to 1e-12"
  fi
done
[ $failed -eq 0 ] && echo "ok: $half + $half steps with a restart match $steps steps in one go"
exit $failed

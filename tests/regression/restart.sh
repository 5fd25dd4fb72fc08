#!/usr/bin/env bash
# Usage: restart.sh [-n RANKS -m MPIEXEC] RBC_IFEM PRM NUMDIFF
#
# Checkpoint and restart of a flowing run in three legs: with n the Output
# interval of PRM, runs 3n steps in one go, and again as n steps (writing a
# checkpoint), a resume to 2n and a resume of the resume to 3n, and
# requires the tables of both to agree to 1e-12 (relative). The second leg
# must have kept the first leg's checkpoint as checkpoint_previous.bin.
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
prm=$2
numdiff=$3

set_launcher "$ranks" "$mpiexec"
enter_scratch_directory

leg=$(sed -n 's/^ *set Output interval *= *//p' "$prm")
steps=$((3 * leg))
# PRM with the entries given here appended: a later entry wins.
variant() { # directory steps resume
  cat "$prm"
  printf 'set Output directory = %s\n' "$1"
  printf 'subsection Time\n  set Number of steps = %s\nend\n' "$2"
  printf 'subsection Immersed cells\n  set Checkpoint interval = %s\n  set Resume = %s\nend\n' "$leg" "$3"
}
variant straight "$steps" false >straight.prm
variant restarted "$leg" false >first_leg.prm
variant restarted $((2 * leg)) true >second_leg.prm
variant restarted "$steps" true >third_leg.prm

failed=0
for run in straight first_leg second_leg third_leg; do
  echo "== $run"
  "${launcher[@]}" "$exe" $run.prm >$run.log 2>&1 || { cat $run.log; echo "FAILED: $run"; exit 1; }
  grep -e "resumed" -e "summary" $run.log
  if [ $run = second_leg ] && [ ! -s restarted/checkpoint_previous.bin ]; then
    echo "FAILED: the second leg did not keep the first leg's checkpoint as checkpoint_previous.bin"
    failed=1
  fi
done

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
[ $failed -eq 0 ] && echo "ok: $leg + $leg + $leg steps with two resumes match $steps steps in one go"
exit $failed

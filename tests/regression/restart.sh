#!/usr/bin/env bash
# Usage: restart.sh [-n RANKS -m MPIEXEC] [-l "R1 R2 R3" -r TOLERANCE] RBC_IFEM PRM NUMDIFF
#
# Checkpoint and restart of a flowing run in three legs: with n the Output
# interval of PRM, runs 3n steps in one go, and again as n steps (writing a
# checkpoint), a resume to 2n and a resume of the resume to 3n, and
# requires the tables of both to agree to 1e-12 (relative). The second leg
# must have kept the first leg's checkpoint as checkpoint_previous.bin.
#
# With -l the three legs run on R1, R2 and R3 ranks (a checkpoint read on
# another number of ranks than wrote it), the run in one go on RANKS; the
# tables then agree to the solver's tolerance, TOLERANCE (relative; 1e-10
# absolute, as compare_run.sh), but for the iteration counts.
set -u
source "$(dirname "$0")/../script_setup.sh"
legs=
tolerance=1e-12
absolute=1e-14
ranks=
mpiexec=
while getopts "n:m:l:r:" option; do
  case $option in
    n) ranks=$OPTARG ;;
    m) mpiexec=$OPTARG ;;
    l) legs=$OPTARG ;;
    r) tolerance=$OPTARG absolute=1e-10 ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
exe=$1
prm=$2
numdiff=$3

enter_scratch_directory
# The ranks of each run: straight and the three legs.
read -r -a leg_ranks <<<"${legs:-$ranks $ranks $ranks}"
declare -A run_ranks=([straight]=$ranks [first_leg]=${leg_ranks[0]:-}
  [second_leg]=${leg_ranks[1]:-} [third_leg]=${leg_ranks[2]:-})

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
  echo "== $run${run_ranks[$run]:+ on ${run_ranks[$run]} rank(s)}"
  set_launcher "${run_ranks[$run]}" "$mpiexec"
  "${launcher[@]}" "$exe" $run.prm >$run.log 2>&1 || { cat $run.log; echo "FAILED: $run"; exit 1; }
  grep -e "resumed" -e "summary" $run.log
  if [ $run = second_leg ] && [ ! -s restarted/checkpoint_previous.bin ]; then
    echo "FAILED: the second leg did not keep the first leg's checkpoint as checkpoint_previous.bin"
    failed=1
  fi
done

# The columns of CSV file $1 but those of iteration counts, which differ
# between numbers of ranks.
without_iterations() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) keep[i] = ($i !~ /iterations/) }
           { line = ""; for (i = 1; i <= NF; ++i) if (keep[i]) line = line (line == "" ? "" : ",") $i; print line }' "$1"
}
if [ -n "$legs" ]; then
  for table in flow.csv cells.csv dm.csv; do
    for run in straight restarted; do
      without_iterations $run/$table >$run/$table.compared && mv $run/$table.compared $run/$table
    done
  done
fi

for table in flow.csv cells.csv dm.csv; do
  if ! "$numdiff" -q -s ' \t\n,' -r "$tolerance" -a "$absolute" straight/$table restarted/$table; then
    echo "FAILED: $table of the restarted run differs from the straight run:"
    "$numdiff" -s ' \t\n,' -r "$tolerance" -a "$absolute" straight/$table restarted/$table | head -20
    failed=1
  elif cmp -s straight/$table restarted/$table; then
    echo "$table: identical"
  else
    echo "$table: equal to $tolerance"
  fi
done
[ $failed -eq 0 ] && echo "ok: $leg + $leg + $leg steps with two resumes match $steps steps in one go"
exit $failed

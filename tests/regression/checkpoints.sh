#!/usr/bin/env bash
# Usage: checkpoints.sh RBC_IFEM PRM NUMDIFF
#
# What a checkpoint must refuse and survive, on the flowing run PRM (one
# rank): a checkpoint with bytes changed in its middle, a truncated one, and
# one written with another Cells/Surface refinements are refused (exit 1,
# nothing resumed) with a message naming the reason or the parameter; a run
# sent SIGTERM writes a checkpoint, exits with status 143 and a message, and
# its resume ends with the tables of a run that was never interrupted. Every
# progress line of the straight run says "step k of N, t = ... of ... s" and
# ends with the wall time and the time left.
set -u
source "$(dirname "$0")/../script_setup.sh"
exe=$1
prm=$2
numdiff=$3
enter_scratch_directory

steps=$(sed -n 's/^ *set Number of steps *= *//p' "$prm")
variant() { # directory steps resume [more entries for Immersed cells]
  cat "$prm"
  printf 'set Output directory = %s\n' "$1"
  printf 'subsection Time\n  set Number of steps = %s\nend\n' "$2"
  printf 'subsection Immersed cells\n  set Checkpoint interval = 1000\n  set Resume = %s\nend\n' "$3"
}

# The straight run, and its progress lines.
variant straight "$steps" false >straight.prm
"$exe" straight.prm >straight.log 2>&1 || { cat straight.log; echo "FAILED: straight run"; exit 1; }
progress=$(grep -c '^  step [0-9]* of '"$steps"', t = [0-9.e-]* of [0-9.e-]* s: .*  \[wall [0-9.]* \(s\|min\|h\)[^]]*, about .* left\]$' straight.log)
lines=$(grep -c '^  step ' straight.log)
echo "progress lines of the form 'step k of $steps, t = .. of .. s: ... [wall .., about .. left]': $progress of $lines"
[ "$progress" -gt 0 ] && [ "$progress" -eq "$lines" ] || fail "progress lines: $(grep '^  step ' straight.log | head -2)"
grep -q "^  summary: t = .* s, $steps steps in " straight.log || fail "no end-of-run summary"
grep -q "^  DM at t = 0 s .* mL/(min mmHg)" straight.log || fail "no DM in the summary"

# A checkpoint to damage: the run's own, after its last step.
cp straight/checkpoint.bin good.bin
size=$(stat -c %s good.bin)
resume_refused() { # name file expected-words
  mkdir -p $1 && cp "$2" $1/checkpoint.bin
  variant $1 $((steps + 5)) true >$1.prm
  "$exe" $1.prm >$1.log 2>&1
  local status=$?
  if [ $status -ne 1 ]; then
    fail "resuming from the $1 checkpoint exits with status $status, not 1"
  elif ! grep -q "$3" $1.log; then
    fail "the $1 checkpoint is refused without saying '$3': $(cat $1.log | tail -2)"
  elif grep -q "resumed" $1.log || [ -e $1/flow.csv ]; then
    fail "the $1 checkpoint was refused after the run had started"
  else
    echo "ok: the $1 checkpoint is refused: $(grep 'error' $1.log)"
  fi
}
cp good.bin corrupted.bin
printf 'XXXXXXXX' | dd of=corrupted.bin bs=1 seek=$((size / 2)) conv=notrunc status=none
resume_refused corrupted corrupted.bin "damaged"
head -c $((size - 1000)) good.bin >truncated.bin
resume_refused truncated truncated.bin "truncated"
mkdir -p changed && cp good.bin changed/checkpoint.bin
{ variant changed $((steps + 5)) true
  printf 'subsection Cells\n  set Surface refinements = 3\nend\n'
  printf 'subsection Mesh\n  set Diffusion band refinements = 2\nend\n'; } >changed.prm
"$exe" changed.prm >changed.log 2>&1
status=$?
[ $status -eq 1 ] && grep -q "parameter 'Cells/Surface refinements' = '3'.*written by a run with Cells/Surface refinements = 2" changed.log \
  && echo "ok: a resume with another Surface refinements is refused: $(grep error changed.log | cut -c1-160)..." \
  || fail "a resume with another Surface refinements: status $status, $(tail -2 changed.log)"

# SIGTERM during a long run: a checkpoint, status 143, a message; then the
# resume to the straight run's end gives the straight run's tables.
variant interrupted 100000 false >long.prm
"$exe" long.prm >long.log 2>&1 &
pid=$!
for _ in $(seq 600); do grep -q "^  step " long.log && break; sleep 0.1; done
kill -TERM $pid
wait $pid
status=$?
[ $status -eq 143 ] || fail "the run sent SIGTERM exits with status $status, not 143"
grep -q "interrupted: SIGTERM at step [0-9]*" long.log || fail "no message on SIGTERM: $(tail -2 long.log)"
[ -s interrupted/checkpoint.bin ] || fail "SIGTERM left no checkpoint"
at=$(sed -n 's/.*SIGTERM at step \([0-9]*\).*/\1/p' long.log)
echo "SIGTERM at step $at of the interrupted run: $(grep interrupted: long.log | cut -c1-120)..."
if [ -n "$at" ] && [ "$at" -lt "$steps" ]; then
  variant interrupted "$steps" true >resume.prm
  "$exe" resume.prm >resume.log 2>&1 || fail "the resume after SIGTERM: $(tail -2 resume.log)"
  for table in flow.csv cells.csv dm.csv; do
    "$numdiff" -q -s ' \t\n,' -r 1e-12 -a 1e-14 straight/$table interrupted/$table \
      && echo "ok: $table after SIGTERM and resume equals the straight run's" \
      || fail "$table after SIGTERM and resume differs from the straight run's"
  done
else
  fail "the run was interrupted at step '${at}', not before step $steps"
fi
[ $failed -eq 0 ] && echo "ok: checkpoints refuse damage and other parameters, and survive SIGTERM"
exit $failed

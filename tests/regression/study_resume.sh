#!/usr/bin/env bash
# Usage: study_resume.sh RBC_IFEM PRM NUMDIFF
#
# A study (PRM: a flowing layouts study of two runs, one rank) stopped by
# SIGTERM in its second run and resumed with the command its message gives
# ends with the tables of the study run in one go: the first run, finished,
# only gives back its results (it resumes at its last step), the second
# goes on from its checkpoint. Then a second start of the study without
# Resume is refused and changes nothing.
set -u
source "$(dirname "$0")/../script_setup.sh"
exe=$1
prm=$2
numdiff=$3
enter_scratch_directory

variant() { # directory
  cat "$prm"
  printf 'set Output directory = %s\n' "$1"
}
variant whole >whole.prm
"$exe" whole.prm >whole.log 2>&1 || { cat whole.log; echo "FAILED: the study in one go"; exit 1; }

variant stopped >stopped.prm
"$exe" stopped.prm >stopped.log 2>&1 &
pid=$!
for _ in $(seq 1200); do
  sed -n '/^run 2 of /,$p' stopped.log | grep -q "^  step " && break
  sleep 0.1
done
kill -TERM $pid
wait $pid
status=$?
message=$(grep "interrupted:" stopped.log)
echo "stopped: status $status, $message"
[ $status -eq 143 ] || fail "the study sent SIGTERM exits with status $status, not 143"
command=$(echo "$message" | sed -n 's/.*To go on from there (in this folder): \(rbc-ifem .*\)$/\1/p')
[ -n "$command" ] || { fail "no command to go on in: $message"; exit 1; }
eval "\"$exe\" ${command#rbc-ifem }" >resumed.log 2>&1 || fail "the resume as the message says: $(tail -2 resumed.log)"
grep "resumed from" resumed.log
[ "$(grep -c 'resumed from checkpoint.bin at step' resumed.log)" -eq 2 ] \
  || fail "both runs should resume from their checkpoints"

same() { # file, compared to the study in one go
  if "$numdiff" -q -s ' \t\n,' -r 1e-12 -a 1e-14 whole/$1 stopped/$1; then
    echo "ok: $1 equals the study in one go"
  else
    fail "$1 differs from the study in one go"
    "$numdiff" -s ' \t\n,' -r 1e-12 -a 1e-14 whole/$1 stopped/$1 | head -8
  fi
}
same flowing_layouts.csv
for study in whole stopped; do # all but wall_seconds, the last column
  rev $study/flowing_layouts_summary.csv | cut -d, -f2- | rev >$study/summary_without_wall.csv
done
same summary_without_wall.csv
for run in $(cd whole && ls -d */); do
  for table in flow.csv cells.csv dm.csv; do same $run$table; done
done

(cd stopped && find . -type f -exec md5sum {} + >../stopped.md5)
"$exe" stopped.prm >again.log 2>&1
status=$?
[ $status -eq 1 ] && grep -q "holds the checkpoints of an earlier run" again.log \
  && (cd stopped && md5sum --quiet -c ../stopped.md5) \
  && echo "ok: the study started again without Resume is refused, its files untouched" \
  || fail "the study started again without Resume: status $status, $(tail -1 again.log)"
[ $failed -eq 0 ] && echo "ok: a study stopped by SIGTERM and resumed as its message says equals the study in one go"
exit $failed

#!/usr/bin/env bash
# Usage: damaged_block.sh -m MPIEXEC RBC_IFEM PRM
#
# A checkpoint written on 2 ranks whose last fluid block is damaged (8
# bytes changed 5,000 bytes before its end, a block that only one rank
# reads), with no checkpoint_previous.bin to fall back to: a resume on 2 and
# on 3 ranks is refused on every rank together, with status 1 and the
# reason, before the run starts (not left waiting in a collective).
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
prm=$2
enter_scratch_directory

variant() { # steps resume
  cat "$prm"
  printf 'set Output directory = run\n'
  printf 'subsection Time\n  set Number of steps = %s\nend\n' "$1"
  printf 'subsection Immersed cells\n  set Checkpoint interval = 4\n  set Resume = %s\nend\n' "$2"
}
variant 4 false >first.prm
variant 8 true >resume.prm
set_launcher 2 "$mpiexec"
"${launcher[@]}" "$exe" first.prm >first.log 2>&1 || { cat first.log; echo "FAILED: the run that writes the checkpoint"; exit 1; }
[ "$(sed -n 's/^blocks //p' run/checkpoint.bin | head -1)" = 2 ] || fail "the checkpoint of 2 ranks does not hold 2 blocks"
rm -f run/checkpoint_previous.bin
size=$(stat -c %s run/checkpoint.bin)
printf 'XXXXXXXX' | dd of=run/checkpoint.bin bs=1 seek=$((size - 5000)) conv=notrunc status=none
for ranks in 2 3; do
  set_launcher $ranks "$mpiexec"
  timeout 300 "${launcher[@]}" "$exe" resume.prm >resume_$ranks.log 2>&1
  status=$?
  if [ $status -ne 1 ]; then
    fail "the resume on $ranks ranks exits with status $status, not 1: $(tail -2 resume_$ranks.log)"
  elif ! grep -q "checkpoint.bin: it is damaged" resume_$ranks.log || grep -q "resumed" resume_$ranks.log; then
    fail "the resume on $ranks ranks is not refused as damaged before it starts: $(tail -2 resume_$ranks.log)"
  else
    echo "ok: on $ranks ranks: $(grep error resume_$ranks.log | head -1 | cut -c1-160)..."
  fi
done
exit $failed

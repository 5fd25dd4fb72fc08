#!/usr/bin/env bash
# Usage: faults.sh RBC_IFEM PRM NUMDIFF
#
# What nothing-lost means for a flowing run PRM (one rank, a checkpoint
# every 2 steps):
#  - killed (SIGKILL, injected by strace) at each moment of a checkpoint's
#    rotation, the run leaves a checkpoint to resume from, and the resume
#    ends with the tables of the run that was never interrupted;
#  - a checkpoint.bin that is gone: the resume uses checkpoint_previous.bin
#    and says so;
#  - a second run into the same Output directory without Resume is refused
#    (status 1) and leaves every file as it was; with --overwrite it runs;
#  - a read-only Output directory is refused at input (status 1) and a full
#    disk stops the run with status 3, the file and "No space left on
#    device", and no .part left (both on a small tmpfs: skipped with a
#    message where this machine may not mount one); on two ranks the full
#    disk stops both together, without MPI_Abort.
set -u
source "$(dirname "$0")/../script_setup.sh"
exe=$1
prm=$2
numdiff=$3
enter_scratch_directory

steps=$(sed -n 's/^ *set Number of steps *= *//p' "$prm")
variant() { # directory resume
  cat "$prm"
  printf 'set Output directory = %s\n' "$1"
  printf 'subsection Immersed cells\n  set Checkpoint interval = 2\n  set Resume = %s\nend\n' "$2"
}
same_tables() { # directory what
  for table in flow.csv cells.csv dm.csv; do
    "$numdiff" -q -s ' \t\n,' -r 1e-12 -a 1e-14 straight/$table $1/$table \
      || { fail "$2: $table differs from the straight run's"; return; }
  done
  echo "ok: $2: the tables equal the straight run's"
}

variant straight false >straight.prm
"$exe" straight.prm >straight.log 2>&1 || { cat straight.log; echo "FAILED: straight run"; exit 1; }

# SIGKILL at the second checkpoint's rotation: at the syscall that strace
# OPTIONS name (DIR stands for the run's directory, ABS for its absolute
# path, which a descriptor's path is), with the first checkpoint on the disk.
killed_at() { # name strace-options...
  local name=$1
  shift
  variant $name false >$name.prm
  local options=("${@//ABS/$PWD/$name}")
  strace -f -o /dev/null "${options[@]//DIR/$name}" "$exe" $name.prm >$name.log 2>&1 &
  wait $! 2>/dev/null
  local status=$?
  [ $status -eq 137 ] || { fail "$name: the injected SIGKILL gave status $status, not 137"; return; }
  [ -s $name/checkpoint.bin ] || { fail "$name: no checkpoint.bin after the kill: $(ls $name)"; return; }
  variant $name true >$name-resume.prm
  "$exe" $name-resume.prm >$name-resume.log 2>&1 || { fail "$name: the resume: $(tail -2 $name-resume.log)"; return; }
  echo "killed $name, then $(grep resumed $name-resume.log | sed 's/^ *//')"
  same_tables $name "killed $name"
}
if strace -o /dev/null true 2>/dev/null; then
  killed_at while-writing -P ABS/checkpoint.bin.part -e trace=fsync -e inject=fsync:signal=KILL:when=2
  killed_at before-link -e trace=link -e inject=link:signal=KILL:when=1
  killed_at before-previous -P DIR/checkpoint_previous.bin.part -e trace=rename \
    -e inject=rename:signal=KILL:when=1
  killed_at before-last-rename -P DIR/checkpoint.bin.part -e trace=rename \
    -e inject=rename:signal=KILL:when=2
  killed_at syncing-directory -P ABS -e trace=fsync -e inject=fsync:signal=KILL:when=2
else
  echo "skipped: strace cannot trace here, so no SIGKILL is injected"
fi

# Without checkpoint.bin, the resume takes checkpoint_previous.bin.

variant lost false | sed 's/^ *set Number of steps *=.*/  set Number of steps = 4/' >lost.prm
"$exe" lost.prm >lost.log 2>&1 || fail "the run before checkpoint.bin is lost: $(tail -2 lost.log)"
rm -f lost/checkpoint.bin
variant lost true >lost-resume.prm
"$exe" lost-resume.prm >lost-resume.log 2>&1 || fail "the resume without checkpoint.bin: $(tail -2 lost-resume.log)"
grep -q "resumed from checkpoint_previous.bin (checkpoint.bin: it does not exist" lost-resume.log \
  && echo "ok: $(grep resumed lost-resume.log | sed 's/^ *//')" \
  || fail "the resume without checkpoint.bin does not say it took checkpoint_previous.bin: $(grep resumed lost-resume.log)"
same_tables lost "checkpoint.bin lost"

# A second run into the straight run's directory: refused, nothing changed.
(cd straight && md5sum * >../straight.md5)
"$exe" straight.prm >again.log 2>&1
status=$?
[ $status -eq 1 ] && grep -q "holds the checkpoints of an earlier run.*Resume = true.*--overwrite" again.log \
  && (cd straight && md5sum --quiet -c ../straight.md5) \
  && echo "ok: a second run without Resume is refused, its files untouched: $(grep error again.log | cut -c1-150)..." \
  || fail "a second run without Resume: status $status, $(tail -1 again.log)"
"$exe" straight.prm --overwrite >overwrite.log 2>&1 && grep -q "removed the 2 checkpoint" overwrite.log \
  && echo "ok: --overwrite starts over: $(grep overwrite: overwrite.log | sed 's/^ *//')" \
  || fail "--overwrite: $(tail -2 overwrite.log)"

# A read-only and a full Output directory, on a tmpfs of 400 kB.
if mkdir disk && mount -t tmpfs -o size=400k,ro tmpfs disk 2>/dev/null; then
  trap 'umount disk 2>/dev/null; rm -rf "$work"' EXIT
  variant disk/run false >readonly.prm
  "$exe" readonly.prm >readonly.log 2>&1
  status=$?
  [ $status -eq 1 ] && grep -q "parameter 'Output directory' = 'disk/run'.*Read-only file system" readonly.log \
    && echo "ok: a read-only Output directory: $(grep error readonly.log)" \
    || fail "a read-only Output directory: status $status, $(tail -1 readonly.log)"
  mount -o remount,rw disk
  "$exe" readonly.prm >full.log 2>&1
  status=$?
  parts=$(find disk -name '*.part' | wc -l)
  [ $status -eq 3 ] && grep -q "could not write 'disk/run/.*': No space left on device" full.log && [ "$parts" -eq 0 ] \
    && echo "ok: a full disk: $(grep stopped full.log | cut -c1-160)..." \
    || fail "a full disk: status $status, $parts .part files, $(tail -1 full.log)"
  # On two ranks the ranks stop together: no MPI_Abort.
  rm -rf disk/run
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -np 2 "$exe" readonly.prm >full2.log 2>&1
  status=$?
  [ $status -eq 3 ] && grep -q "No space left on device" full2.log && ! grep -q "MPI_ABORT" full2.log \
    && echo "ok: a full disk on two ranks: status 3, no MPI_Abort" \
    || fail "a full disk on two ranks: status $status, $(grep -c MPI_ABORT full2.log) MPI_ABORT lines, $(grep stopped full2.log | head -1)"
  # Room for parameters.prm alone: the first DM solve's fields fail.
  rm -rf disk/run
  mount -o remount,size=48k disk
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun -np 2 "$exe" readonly.prm >full3.log 2>&1
  status=$?
  [ $status -eq 3 ] && grep -q "could not write 'disk/run/diffusion_0000.*No space left on device" full3.log \
    && ! grep -q "MPI_ABORT" full3.log \
    && echo "ok: the DM fields on a full disk, two ranks: status 3, no MPI_Abort" \
    || fail "the DM fields on a full disk, two ranks: status $status, $(grep stopped full3.log | head -1)"
  umount disk
else
  echo "skipped: no tmpfs can be mounted here for the read-only and full disk"
fi
[ $failed -eq 0 ] && echo "ok: nothing lost at a kill, a rerun, a read-only or a full disk"
exit $failed

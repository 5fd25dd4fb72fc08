# Sourced by the script tests that run rbc-ifem (compare_run.sh, restart.sh, ...).

# read_rank_options "$@": the options -n RANKS -m MPIEXEC of a script into
# `ranks` and `mpiexec` (empty when not given); the script then shifts its
# arguments by $((OPTIND - 1)).
read_rank_options() {
  ranks=
  mpiexec=
  local option
  while getopts "n:m:" option; do
    case $option in
      n) ranks=$OPTARG ;;
      m) mpiexec=$OPTARG ;;
      *) exit 2 ;;
    esac
  done
}

# set_launcher RANKS MPIEXEC: the array `launcher` that prefixes a run,
# empty for a serial run (RANKS empty), else MPIEXEC -np RANKS (as root too).
set_launcher() {
  launcher=()
  if [ -n "$1" ]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
    launcher=("$2" -np "$1")
  fi
}

# Move into a new empty directory, removed when the script exits.
enter_scratch_directory() {
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  cd "$work" || exit 1
}

# fail MESSAGE: print it as a failure and mark the script failed (failed=1;
# the script exits with $failed at its end).
failed=0
fail() { echo "FAILED: $*"; failed=1; }

# Sourced by the script tests that run rbc-ifem (compare_run.sh, restart.sh).

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

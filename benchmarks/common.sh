# Sourced by the benchmark scripts: `benchmark_setup "$@"` sets exe (the
# rbc-ifem program, default build/rbc-ifem) and ranks (default 1) from the
# script's arguments, allows mpirun as root, and moves into a temporary
# directory that is removed on exit.
benchmark_setup() {
  local here
  here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  exe=$(realpath "${1:-$here/build/rbc-ifem}")
  ranks=${2:-1}
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  cd "$work"
}

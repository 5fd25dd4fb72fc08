#!/usr/bin/env bash
# Usage: last_good.sh -m MPIEXEC RBC_IFEM SOURCE_DIR
#
# A flowing run that stops as diverged writes the last good membranes of
# every cell, each by its owner: four cells in a periodic 20 µm segment on
# 2 ranks (two cells each), stopped after its first step by a Maximum volume
# change no cell keeps to. Checks that the run exits with a non-zero status
# and names last_good_cell_*.vtu, and that every cell's file is there, whole
# (it ends with the VTK file's closing tag).
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$(realpath "$1")
source_dir=$(realpath "$2")
enter_scratch_directory

set_launcher 2 "$mpiexec"
"${launcher[@]}" "$exe" "$source_dir/prm/default.prm" \
  --set "Output directory=stopped" --set "Layout/Number of cells=4" \
  --set "Geometry/Periodic=true" --set "Geometry/Capillary length=20" \
  --set "Time/Number of steps=3" --set "Immersed cells/Diffusion interval=0" \
  --set "Immersed cells/Maximum volume change=1e-12" >run.log 2>&1
status=$?
[ $status -ne 0 ] || fail "the run that had to stop exits with status 0"
grep -q "last_good_cell_" run.log || { cat run.log; fail "the run does not name the last good membranes"; }
for c in 0 1 2 3; do
  file=$(ls stopped/last_good_cell_${c}_*.vtu 2>/dev/null | head -1)
  if [ -z "$file" ]; then
    fail "no last_good_cell_${c}_*.vtu in stopped/: $(ls stopped | tr '\n' ' ')"
  elif tail -c 64 "$file" | grep -q "</VTKFile>"; then
    echo "ok: $file is written whole"
  else
    fail "$file does not end with </VTKFile>"
  fi
done
exit $failed

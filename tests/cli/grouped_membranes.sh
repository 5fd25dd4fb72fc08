#!/usr/bin/env bash
# Usage: grouped_membranes.sh -m MPIEXEC RBC_IFEM SOURCE_DIR PYTHON3
#
# Immersed cells/Membrane files = grouped against per cell: two coarse cells
# (tests/regression/parachute_small, 4 steps, an output every 2) written per
# cell on 1 rank, and grouped on 2 ranks (one cell each) and on 3 (fewer
# cells than ranks: one rank owns none and writes no piece). Read with
# VTK's XML readers, checks that
#  (a) membranes.pvd lists the times of cell_0.pvd and every file exists;
#  (b) each membranes_SSSS.pvtu joins one piece per rank that owns cells,
#      and no other piece was written;
#  (c) the grouped membranes hold each cell exactly once: for every cell
#      index c, as many points and cells as cell_c_SSSS.vtu, at the same
#      places within 1e-6 µm (the runs on other rank counts agree to the
#      solver tolerance), with the same fields;
#  (d) the fields of the two kinds of file are the same: displacement,
#      force, force_density, area_change and cell.
# Every number it checks is printed.
set -u
source "$(dirname "$0")/../script_setup.sh"
read_rank_options "$@"
shift $((OPTIND - 1))
exe=$1
source_dir=$(realpath "$2")
python=$3
enter_scratch_directory

run() { # run RANKS FOLDER MEMBRANE_FILES
  set_launcher "$1" "$mpiexec"
  "${launcher[@]}" "$exe" "$source_dir/tests/regression/parachute_small/run.prm" \
    --set "Output directory=$2" --set "Layout/Number of cells=2" \
    --set "Time/Number of steps=4" --set "Time/Output interval=2" \
    --set "Immersed cells/Diffusion interval=0" \
    --set "Immersed cells/Membrane files=$3" >"$2.log" 2>&1
  local status=$?
  [ $status -eq 0 ] || { cat "$2.log"; fail "the run on $1 rank(s) with $3 exits with status $status"; }
}
run 1 per_cell "per cell"
run 2 grouped2 grouped
run 3 grouped3 grouped
[ $failed -eq 0 ] || exit 1

cat >check.py <<'PYTHON'
import glob, os, re, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy

def times(pvd):
    text = open(pvd).read()
    return [(float(t), f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]

def points(grid):
    return vtk_to_numpy(grid.GetPoints().GetData())

def arrays(grid):
    data = grid.GetPointData()
    return sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))

def read(path, reader):
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()

failed = False
def check(ok, text):
    global failed
    print(("ok: " if ok else "FAILED: ") + text)
    failed |= not ok

reference = times("per_cell/cell_0.pvd")
for folder, ranks in (("grouped2", 2), ("grouped3", 3)):
    series = times(folder + "/membranes.pvd")
    check([t for t, _ in series] == [t for t, _ in reference],
          f"{folder}: membranes.pvd times {[t for t, _ in series]}, cell_0.pvd's {[t for t, _ in reference]}")
    pieces_written = glob.glob(folder + "/membranes_*.*.vtu")
    n_pieces = 0
    for (time, pvtu), (_, cell_file) in zip(series, reference):
        text = open(os.path.join(folder, pvtu)).read()
        pieces = re.findall(r'Piece Source="([^"]+)"', text)
        n_pieces += len(pieces)
        check(len(pieces) == 2 and all(os.path.exists(os.path.join(folder, p)) for p in pieces),
              f"{folder}/{pvtu}: pieces {pieces} (2 ranks own cells)")
        grouped = read(os.path.join(folder, pvtu), vtk.vtkXMLPUnstructuredGridReader())
        cell_index = vtk_to_numpy(grouped.GetPointData().GetArray("cell"))
        xyz = points(grouped)
        for c in range(2):
            alone = read(os.path.join("per_cell", cell_file.replace("cell_0_", f"cell_{c}_")),
                         vtk.vtkXMLUnstructuredGridReader())
            mine = xyz[cell_index == c]
            expected = points(alone)
            same_count = len(mine) == len(expected)
            gap = abs(mine - expected).max() if same_count else float("inf")
            check(same_count and gap < 1e-6,
                  f"{folder}/{pvtu} cell {c}: {len(mine)} points (alone {len(expected)}), "
                  f"largest distance {gap:.2e} µm")
        check(arrays(grouped) == arrays(alone),
              f"{folder}/{pvtu} fields {arrays(grouped)}, per cell {arrays(alone)}")
        check(grouped.GetNumberOfCells() == 2 * alone.GetNumberOfCells(),
              f"{folder}/{pvtu}: {grouped.GetNumberOfCells()} cells of patches, "
              f"2 x {alone.GetNumberOfCells()}")
    check(len(pieces_written) == n_pieces,
          f"{folder}: {len(pieces_written)} piece files written, {n_pieces} listed")
sys.exit(1 if failed else 0)
PYTHON
"$python" check.py || fail "the grouped membranes differ from the per-cell ones"
for folder in grouped2 grouped3; do
  ls $folder | grep -q '^cell_' && fail "$folder has per-cell files: $(ls $folder | grep '^cell_' | head -3)"
done
exit $failed

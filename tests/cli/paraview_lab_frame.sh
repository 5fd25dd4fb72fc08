#!/usr/bin/env bash
# Usage: paraview_lab_frame.sh RBC_IFEM SOURCE_DIR
#
# doc/scripts/paraview_lab_frame.py under pvbatch, headless: a short flowing
# run of two coarse cells (tests/regression/parachute_small, 20 steps, an
# output every 5), then the script's picture and its lab-frame centres.
# Checks that the picture is a PNG of nonzero size, and that at every step
# each cell's lab-frame centre (the centre in x of its moved membrane's
# bounding box) is
#  (b) cells.csv's x (the volume centroid in the laboratory) within 0.02 µm:
#      the two differ by the cell's asymmetry in x, measured 0.0068 µm at
#      the last step (0.4 ms) and growing with the deformation; the frame
#      moves 0.063 µm in the first 0.1 ms and 0.25 µm by the last step, so
#      centres left in the frame fail at every step but t = 0;
#  (c) the centre of the same membrane read in the frame, plus that step's
#      FRAME_OFFSET, within 1e-6 µm (the 10 digits printed).
# Xvfb runs with -noreset: without it Xvfb resets whenever its last client
# disconnects, and about one pvbatch in ten aborted ("bad X server
# connection"; none in 55 runs with it).
set -u
exe=$1
source_dir=$2
. "$source_dir/tests/script_setup.sh"
enter_scratch_directory
tolerance_centroid=0.02
tolerance_offset=1e-6

"$exe" "$source_dir/tests/regression/parachute_small/run.prm" --set "Output directory=run" \
  --set "Layout/Number of cells=2" --set "Time/Output interval=5" >run.log 2>&1
status=$?
[ $status -eq 0 ] || { cat run.log; fail "the run exits with status $status"; exit 1; }

headless=(xvfb-run -a -s -noreset pvbatch)
"${headless[@]}" "$source_dir/doc/scripts/paraview_lab_frame.py" run --save picture.png \
  --print-centres >centres.txt 2>pvbatch.log
status=$?
if [ $status -ne 0 ]; then
  cat centres.txt pvbatch.log
  grep -q "No module named 'paraview'" pvbatch.log && echo "pvbatch has no Python modules: apt-get install python3-paraview"
  fail "paraview_lab_frame.py exits with status $status"
  exit 1
fi
grep -q "^time,cell,lab_x_centre$" centres.txt || fail "no header time,cell,lab_x_centre"

# (a) The PNG signature, a nonzero width and height in its IHDR chunk, and
# the IEND chunk at its end.
signature=$(head -c 8 picture.png 2>/dev/null | od -An -tx1 | tr -d ' \n')
[ "$signature" = 89504e470d0a1a0a ] || fail "picture.png is not a PNG (starts with '$signature')"
read -r width height < <(od -An -tu1 -j16 -N8 picture.png 2>/dev/null |
  awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4, $5 * 16777216 + $6 * 65536 + $7 * 256 + $8 }')
[ "${width:-0}" -gt 0 ] && [ "${height:-0}" -gt 0 ] || fail "picture.png is ${width:-?} x ${height:-?} pixels"
tail -c 8 picture.png | grep -q IEND || fail "picture.png does not end with IEND"
echo "picture.png: $width x $height pixels, $(stat -c %s picture.png) bytes"

# Each cell's bounding-box centre and FRAME_OFFSET, read in the frame by
# ParaView's reader alone.
cat >frame.py <<'EOF'
import glob, re, sys
from paraview import simple as pv
print("time,cell,frame_x_centre,frame_offset")
for path in glob.glob(sys.argv[1] + "/cell_*.pvd"):
    reader = pv.PVDReader(FileName=path)
    times = reader.TimestepValues
    for t in times if hasattr(times, "__len__") else [times]:
        reader.UpdatePipeline(t)
        bounds = reader.GetDataInformation().GetBounds()
        offset = reader.FieldData["FRAME_OFFSET"].GetRange()[0]
        cell = re.search(r"cell_([0-9]+)\.pvd$", path).group(1)
        print(f"{t:.10g},{cell},{0.5 * (bounds[0] + bounds[1]):.10g},{offset:.10g}")
EOF
"${headless[@]}" frame.py run >frame.txt 2>frame.log
status=$?
[ $status -eq 0 ] || { cat frame.log; fail "frame.py exits with status $status"; exit 1; }

# (b) and (c), every printed step of every cell.
awk -F, -v tb="$tolerance_centroid" -v tc="$tolerance_offset" '
  function key(t, c) { return sprintf("%.8g %d", t, c) }
  function abs(v) { return v < 0 ? -v : v }
  FNR == 1 { file++; for (i = 1; i <= NF; i++) column[file, $i] = i; next }
  file == 1 { x[key($column[1, "time"], $column[1, "cell"])] = $column[1, "x"]; next }
  file == 2 { k = key($1, $2); frame[k] = $3; offset[k] = $4; next }
  {
    k = key($1, $2); checked++
    if (!(k in x) || !(k in frame)) { print "FAILED: step " k " is not in cells.csv or the frame files"; bad = 1; next }
    centroid = $3 - x[k]; moved = $3 - frame[k] - offset[k]
    printf "t = %s s, cell %d: lab-frame centre %.6f µm, cells.csv x %.6f (difference %+.4f), frame centre %.6f + FRAME_OFFSET %.6f (difference %+.1e)\n",
      $1, $2, $3, x[k], centroid, frame[k], offset[k], moved
    if (abs(centroid) > tb) { print "FAILED: the lab-frame centre is not cells.csv x within " tb " µm"; bad = 1 }
    if (abs(moved) > tc) { print "FAILED: the lab-frame centre is not the frame centre + FRAME_OFFSET within " tc " µm"; bad = 1 }
    if (offset[k] > largest) largest = offset[k]
  }
  END {
    if (checked != 10) { print "FAILED: " checked " centres, not 2 cells x 5 steps"; bad = 1 }
    if (largest < 5 * tb) { print "FAILED: the frame moved " largest " µm: too little to test the transform"; bad = 1 }
    exit bad
  }' run/cells.csv frame.txt \
  <(grep -E '^(time,cell,lab_x_centre|[-0-9.e+]+,[0-9]+,[-0-9.e+]+)$' centres.txt) ||
  failed=1

[ $failed -eq 0 ] && echo "ok: the membranes in the laboratory frame follow cells.csv and FRAME_OFFSET"
exit $failed

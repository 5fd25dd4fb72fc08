#!/usr/bin/env bash
# Usage: benchmarks/step70_anchor.sh [RBC_IFEM] [RANKS, default 2]
#
# An anchor for the speed of our immersed time step: deal.II's own step-70
# tutorial (an immersed solid in Stokes flow, Q2-Q1, Trilinos AMG), built
# unmodified from the Debian package libdeal.ii-doc, in 3-D at about the
# DoFs of our paper-size run, against our paper-size parachute (the default
# experiment with Mesh/Fluid band refinements = 2, Band width = 2.5 µm,
# Cells/Surface refinements = 5: 244,862 fluid DoFs, 6,146 membrane points),
# on the same ranks in this one run. The seconds of one warm step are the
# difference of two runs, one step more against one step less, so that
# setup and output are left out on both sides. Prints both and
# `ratio: X`, step-70's seconds per step over ours, and adds them to
# doc/results/benchmarks/step70_anchor.csv (benchmarks/common.sh). About 4
# minutes on 2 ranks.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
benchmark_setup "${1:-}" "${2:-2}"

examples=/usr/share/doc/libdeal.ii-doc/examples
[ -f "$examples/step-70/step-70.cc" ] ||
  { echo "step70_anchor: needs the Debian package libdeal.ii-doc" >&2; exit 1; }
cp -r "$examples/step-70" step-70
(cd step-70 && cmake -DCMAKE_BUILD_TYPE=Release . >/dev/null && make >/dev/null 2>&1) ||
  { echo "step70_anchor: building step-70 failed" >&2; exit 1; }

# step-70 in 3-D (its main() takes a file name with a 3 as the 3-D case):
# the unit cube cut into 21³ cells, Q2-Q1, 249,169 DoFs; the default solid
# and tracers of its 3-D case; no remeshing within the run.
step70_prm() {
  cat <<PRM
subsection Stokes Immersed Problem
  set Final time                    = 1
  set Initial fluid refinement      = 0
  set Initial solid refinement      = 3
  set Particle insertion refinement = 1
  set Number of time steps          = $1
  set Output frequency              = 1000
  set Velocity degree               = 2
  set Output directory              = out70
  subsection Grid generation
    set Fluid grid generator           = subdivided_hyper_rectangle
    set Fluid grid generator arguments = 21, 21, 21 : -1, -1, -1 : 1, 1, 1 : false
  end
  subsection Refinement and remeshing
    set Refinement step frequency = 1000
  end
end
PRM
}
mkdir -p out70
# seconds LOG COMMAND...: the wall time of COMMAND, its output in LOG.
seconds() { local log=$1; shift; /usr/bin/env time -f "%e" -o t.txt "$@" >"$log" 2>&1; cat t.txt; }
step70() {
  step70_prm "$1" > parameters_3d.prm
  seconds step70.log mpirun -np "$ranks" step-70/step-70 parameters_3d.prm
}
ours() {
  seconds ours.log mpirun -np "$ranks" "$exe" "$here/prm/default.prm" \
    --set "Mesh/Fluid band refinements=2" --set "Mesh/Band width=2.5" \
    --set "Cells/Surface refinements=5" --set "Immersed cells/Coupling=explicit" \
    --set "Time/Time step=4e-6" --set "Time/Number of steps=$1" \
    --set "Immersed cells/Diffusion interval=0" \
    --set "Immersed cells/Progress interval=1000" \
    --set "Immersed cells/Checkpoint interval=0" \
    --set "Time/Output interval=1000" --set "Output directory=ours"
}
step70_one=$(step70 2); step70_two=$(step70 3)
ours_few=$(ours 5); ours_more=$(ours 25)
step70_dofs=$(sed -n 's/.*Number of degrees of freedom: *\([0-9]*\).*/\1/p' step70.log | head -1)
read -r s70 ours ratio < <(awk -v a="$step70_one" -v b="$step70_two" -v c="$ours_few" -v d="$ours_more" 'BEGIN {
  s70 = b - a; s = (d - c) / 20; printf "%.2f %.3f %.1f\n", s70, s, s70 / s }')
echo "step-70 (3-D, $step70_dofs DoFs), $ranks ranks: $s70 s per step"
echo "rbc-ifem paper-size parachute (244862 DoFs), $ranks ranks: $ours s per step"
echo "ratio: $ratio"
echo
results_table step70_anchor ranks "step-70 DoFs" "step-70 [s per step]" "rbc-ifem DoFs" "rbc-ifem [s per step]" ratio
results_row "$ranks" "$step70_dofs" "$s70" 244862 "$ours" "$ratio"

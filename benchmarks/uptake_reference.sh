#!/usr/bin/env bash
# Usage: benchmarks/uptake_reference.sh [RBC_IFEM] [RANKS, default 2]
#
# The uptake solve against its yardstick (issue 50's target: the seven-cell
# DM solve at most 1.5 times a Q2 Poisson solve with ML AMG on the same
# mesh). For each case, in this one run of the script:
# - the DM solve of rbc-ifem (`Experiment = diffusion`, cut cells, Q2, the
#   default mesh), the fastest of three runs, by phase from its timing.csv;
# - benchmarks/poisson_reference (built here against rbc-ifem installed
#   from RBC_IFEM's build folder): -ΔP = 1 in FE_Q(2) on the very mesh that
#   DM solve ended with, the same AMG settings, scaling and CG tolerance,
#   the fastest of three runs.
# Cases: one resting cell in the default 20 µm capillary (prm/default.prm's
# geometry), and seven uniform cells in the periodic segment (the first DM
# instant of prm/flowing_layouts.prm's seven-cell runs). Prints the phases
# side by side, then DM over reference for the whole solve (DM: mesh, level
# set, cut cells, DoFs, assembly, AMG, CG; reference: DoFs to CG on the
# given mesh) and per DoF. Rows go to doc/results/benchmarks/
# uptake_reference.csv (benchmarks/common.sh). About 2 minutes on 2 ranks.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
source "$here/benchmarks/common.sh"
benchmark_setup "${1:-}" "${2:-2}"

build=$(dirname "$exe")
cmake --install "$build" --prefix "$work/prefix" >install.log
cmake -S "$here/benchmarks/poisson_reference" -B reference-build \
  -DCMAKE_PREFIX_PATH="$work/prefix" >configure.log
cmake --build reference-build >build.log 2>&1 ||
  { cat build.log; echo "uptake_reference: building poisson_reference failed" >&2; exit 1; }

# case_prm NAME SETTINGS...: prm/default.prm as a DM solve, with SETTINGS
# (lines of a parameter file) after it.
case_prm() {
  local name=$1
  shift
  { cat "$here/prm/default.prm"
    echo "set Experiment = diffusion"
    printf '%s\n' "$@"
  } >"$name.prm"
}
# field LOG NAME: the seconds after NAME in the reference's line in LOG.
field() { sed -n "s/.* $2 \([0-9.e+-]*\) s.*/\1/p" "$1"; }

# compare LABEL SETTINGS...: DM and reference on one case, the fastest of
# three runs each, into dm_LABEL/ (timing.csv) and ref_LABEL.log.
compare() {
  local label=$1 run best
  shift
  case_prm case "$@"
  for run in 1 2 3; do
    mpirun -np "$ranks" "$exe" case.prm --set "Output directory=dm.$run" >"dm.$run.log" 2>"dm.$run.err"
    mpirun -np "$ranks" reference-build/poisson_reference case.prm >"ref.$run.log"
  done
  best=$(for run in 1 2 3; do echo "$(uptake_seconds "dm.$run") $run"; done | sort -g | head -1 | cut -d' ' -f2)
  mv "dm.$best" "dm_$label"
  mv "dm.$best.log" "dm_$label.log"
  best=$(for run in 1 2 3; do echo "$(field "ref.$run.log" total) $run"; done | sort -g | head -1 | cut -d' ' -f2)
  mv "ref.$best.log" "ref_$label.log"
  rm -rf dm.* ref.*
}
# dm_phase DIR PHASE: the seconds of one phase of the DM solve alone (the
# sections that hold others less those).
dm_phase() {
  local d=$1
  case $2 in
    "level set") section_seconds "$d" "diffusion: level set" ;;
    "surface points") section_seconds "$d" "diffusion: surface points" ;;
    "other cut-cell setup") awk -v a="$(section_seconds "$d" "diffusion: setup")" -v b="$(section_seconds "$d" "diffusion: level set")" \
      -v c="$(section_seconds "$d" "diffusion: surface points")" 'BEGIN { printf "%.3f", a - b - c }' ;;
    dofs) awk -v a="$(section_seconds "$d" "diffusion: DoFs and constraints")" -v b="$(section_seconds "$d" "diffusion: sparsity")" \
      'BEGIN { printf "%.3f", a - b }' ;;
    sparsity) section_seconds "$d" "diffusion: sparsity" ;;
    assemble) awk -v a="$(section_seconds "$d" "diffusion: assemble")" -v b="$(section_seconds "$d" "diffusion: AMG setup")" \
      'BEGIN { printf "%.3f", a - b }' ;;
    amg) section_seconds "$d" "diffusion: AMG setup" ;;
    solve) section_seconds "$d" "diffusion: solve" ;;
    mesh) section_seconds "$d" "diffusion mesh" ;;
  esac
}
# ref_phase LOG PHASE: the reference's seconds of PHASE (none: -).
ref_phase() {
  case $2 in
    dofs | sparsity | assemble | amg | solve) printf '%.3f' "$(field "$1" "$2")" ;;
    *) echo - ;;
  esac
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

labels=("one cell" "seven cells, periodic")
compare "${labels[0]}"
compare "${labels[1]}" "subsection Geometry" "  set Periodic = true" "end" \
  "subsection Layout" "  set Number of cells = 7" "end"

results_table uptake_reference ranks case "DM DoFs" "DM CG iterations" "DM [s]" \
  "reference DoFs" "reference CG iterations" "reference [s]" "DM / reference" "DM / reference per DoF"
for label in "${labels[@]}"; do
  read -r dofs_a its_a < <(sed -n 's/.*cells: \([0-9]*\) DoFs, \([0-9]*\) solver iterations.*/\1 \2/p' "dm_$label.log")
  read -r dofs_b its_b < <(sed -n 's/^reference: \([0-9]*\) dofs, \([0-9]*\) iterations.*/\1 \2/p' "ref_$label.log")
  dm=$(uptake_seconds "dm_$label") ref=$(printf '%.3f' "$(field "ref_$label.log" total)")
  results_row "$ranks" "$label" "$dofs_a" "$its_a" "$dm" "$dofs_b" "$its_b" "$ref" "$(ratio "$dm" "$ref")" \
    "$(awk -v a="$dm" -v b="$ref" -v n="$dofs_a" -v m="$dofs_b" 'BEGIN { printf "%.2f", (a / n) / (b / m) }')"
done
echo
results_table uptake_reference_phases ranks case phase "DM [s]" "reference [s]"
for label in "${labels[@]}"; do
  for phase in mesh "level set" "surface points" "other cut-cell setup" dofs sparsity assemble amg solve; do
    results_row "$ranks" "$label" "$phase" "$(dm_phase "dm_$label" "$phase")" "$(ref_phase "ref_$label.log" "$phase")"
  done
done

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

# before_after_setup "$@": for a script that runs two programs side by
# side, BEFORE AFTER [RANKS] [CELLS]: sets before and after (their paths),
# ranks (default 2) and cells (default $default_cells if set, else 64),
# then benchmark_setup.
before_after_setup() {
  [ $# -ge 2 ] || { echo "usage: $0 BEFORE AFTER [RANKS] [CELLS]" >&2; exit 2; }
  before=$(realpath "$1")
  after=$(realpath "$2")
  cells=${4:-${default_cells:-64}}
  benchmark_setup "$after" "${3:-2}"
}

# The results of every benchmark go to doc/results/benchmarks/NAME.csv
# (doc/results/README.md): one header row, then a row per measured line,
# each beginning with the commit the repository had checked out, the date
# and time the script started and the command that ran it, so that every
# run adds its rows and the pages pick theirs (doc/scripts/tables.py). Set
# RBC_IFEM_RESULTS to another folder to keep a run out of doc/results/.
#
# results_setup ARGUMENTS...: the commit, date and command of this run
# (sourcing this file calls it with the script's arguments).
results_setup() {
  local root argument
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  results_dir=${RBC_IFEM_RESULTS:-$root/doc/results/benchmarks}
  results_commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
  results_date=$(date '+%F %H:%M')
  results_source="benchmarks/$(basename "$0")"
  for argument in "$@"; do results_source+=" $argument"; done
  mkdir -p "$results_dir"
}

# csv_field TEXT: TEXT as one CSV field (quoted if it holds a comma or a quote).
csv_field() {
  case $1 in
    *[,\"]*) printf '"%s"' "${1//\"/\"\"}" ;;
    *) printf '%s' "$1" ;;
  esac
}

# markdown_row VALUE...: | VALUE | VALUE | ... |
markdown_row() {
  local line="|" v
  for v in "$@"; do line+=" $v |"; done
  echo "$line"
}

# results_table NAME HEADER...: the rows that follow go to NAME.csv (with
# the header commit,date,source,HEADER... if the file is new); prints the
# Markdown header.
results_table() {
  results_file=$results_dir/$1.csv
  shift
  if [ ! -s "$results_file" ]; then
    local header=commit,date,source h
    for h in "$@"; do header+=,$(csv_field "$h"); done
    echo "$header" >"$results_file"
  fi
  markdown_row "$@"
  printf '|%.0s---' "$@"
  echo "|"
}

# results_row VALUE...: one row of the table results_table started, appended
# to its file with this run's commit, date and command, and printed as
# Markdown.
results_row() {
  local row v
  row=$(csv_field "$results_commit"),$(csv_field "$results_date"),$(csv_field "$results_source")
  for v in "$@"; do row+=,$(csv_field "$v"); done
  echo "$row" >>"$results_file"
  markdown_row "$@"
}

# section_seconds DIR SECTION: the seconds of the TimerOutput SECTION in
# DIR/timing.csv (0.000 if the run has none).
section_seconds() { awk -F, -v s="\"$2\"" '$1 == s { t += $3 } END { printf "%.3f", t }' "$1/timing.csv"; }

# wall_after LOG STEP: the wall time at the end of step STEP of a run whose
# progress lines LOG holds [s] ("[wall 12.3 s" or "[wall 1 min 05 s")
wall_after() {
  sed -n "s/^  step $2 of [0-9]*,.*\[wall \([^,]*\),.*/\1/p" "$1" |
    awk '{print ($2 == "min") ? 60 * $1 + $3 : $1}'
}

# step_seconds LOG: seconds per step of a 3-step run, from the end of step
# 1 to the end of step 3 over 2 (the set-up and the first step's one-off
# work left out), as 12.34.
step_seconds() {
  awk -v a="$(wall_after "$1" 1)" -v b="$(wall_after "$1" 3)" 'BEGIN {printf "%.2f", (b - a) / 2}'
}

# peak_memory LOG: the largest rank's peak memory [MB] of the run's last
# line "peak memory: X MB ...".
peak_memory() { sed -n 's/.*peak memory: \([0-9.e+]*\) MB.*/\1/p' "$1"; }

# per_step LOG WHAT: the largest rank's WHAT per step ("collective MPI calls",
# "bytes sent" or "bytes into collectives") in the program's line "per rank
# and step, least to most over P: A-B collective MPI calls, ..., E-F bytes
# sent, G-H bytes into collectives" of LOG
per_step() {
  sed -n 's/.*per rank and step, least to most over [0-9]*: //p' "$1" |
    tr ',' '\n' | sed -n "s/^ *[0-9.e+]*-\([0-9.e+]*\) $2.*/\1/p" |
    awk '{printf "%.0f", $1}'
}

# cells_difference BEFORE AFTER: the largest difference of a column of
# AFTER/cells.csv from BEFORE's, over the column's largest value, as
# 1.2e-07: columns of round-off about zero (below 1e-6, such as a centred
# cell's y and z) left out, the inclination (an axis's angle, in
# (-π/2, π/2]) compared modulo π.
cells_difference() {
  /usr/bin/python3 - "$1/cells.csv" "$2/cells.csv" <<'PY'
import csv, math, sys
rows = [list(csv.reader(open(f))) for f in sys.argv[1:]]
worst = 0.0
for column, name in enumerate(rows[0][0]):
    try:
        a = [float(r[column]) for r in rows[0][1:]]
        b = [float(r[column]) for r in rows[1][1:]]
    except ValueError:
        continue
    scale = max(abs(v) for v in a + b)
    if scale < 1e-6:  # round-off about zero
        continue
    for x, y in zip(a, b):
        d = abs(x - y)
        if name == "inclination":
            d = min(d, math.pi - d)
        worst = max(worst, d / scale)
print(f"{worst:.1e}")
PY
}

# load_balance LOG WHAT: the least and most per rank of WHAT ("membrane
# points" or "fluid cells") in the program's line "per rank, least to most
# over P: ..., A-B membrane points in its C-D fluid cells" of LOG, as A-B.
load_balance() {
  sed -n "s/.*per rank, least to most over [0-9]*: .* \([0-9]*-[0-9]*\) $2.*/\1/p" "$1" |
    head -1
}

# The sections of a DM solve that hold the others (the level set and the
# surface points are in setup, the sparsity in DoFs and constraints, the
# AMG setup in assemble), without the output.
uptake_sections='"diffusion mesh"|"diffusion: setup"|"diffusion: membrane sampling"|"diffusion: DoFs and constraints"|"diffusion: assemble"|"diffusion: solve"'
# uptake_seconds DIR [EXTRA]: the seconds of the DM solves of DIR/timing.csv,
# their output aside; EXTRA (a regular expression of quoted section names,
# e.g. '"diffusion: output"') adds those sections.
uptake_seconds() {
  local sections=$uptake_sections
  [ -n "${2:-}" ] && sections+="|$2"
  awk -F, -v s="$sections" '$1 ~ s { t += $3 } END { printf "%.3f", t }' "$1/timing.csv"
}

# Haberman & Sayre (1958) for a rigid sphere of radius λR on the axis of a
# tube of radius R, as awk functions: the free sphere's velocity over the
# centre-line velocity in Poiseuille flow, and the drag factor K of a sphere
# towed through fluid at rest (F = 6πμaU K).
haberman_sayre='
  function hs_velocity_ratio(l) { return (1 - 2 / 3 * l^2 - 0.20217 * l^5) / (1 - 0.75857 * l^5) }
  function hs_drag_factor(l) {
    return (1 - 0.75857 * l^5) / (1 - 2.1050 * l + 2.0865 * l^3 - 1.7068 * l^5 + 0.72603 * l^6) }'

# body_fitted LAMBDA: the body-fitted, axisymmetric solution of the same
# sphere (sphere-in-tube-reference, built next to the rbc-ifem program) on
# its finest mesh of 5 refinements, converged to 1e-4 or better: prints K,
# the held drag factor F/(6πμaU_c) and the free sphere's U/U_c.
body_fitted() {
  "$(dirname "$exe")/sphere-in-tube-reference" "$1" 5 | awk -F, 'END { print $5, $6, $7 }'
}

# write_seven_cells_prm METHOD DEGREE SURFACE BAND: run.prm, one CO diffusion
# solve of seven uniform cells (benchmarks/diffusion.sh, diffusion_builds.sh).
write_seven_cells_prm() {
  cat > run.prm <<PRM
set Experiment = diffusion
set Output directory = out
subsection Layout
  set Kind = uniform
  set Number of cells = 7
end
subsection Cells
  set Surface refinements = $3
end
subsection Mesh
  set Diffusion global refinements = 1
  set Diffusion band refinements = $4
end
subsection Diffusion
  set Method = $1
  set Finite element degree = $2
end
PRM
}

results_setup "$@"

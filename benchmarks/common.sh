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

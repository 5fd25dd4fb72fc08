#include <rbc_ifem/fluid/stokes_preconditioner.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

namespace rbc_ifem
{
  StokesPreconditioner::StokesPreconditioner(
    const TrilinosWrappers::BlockSparseMatrix &system_matrix,
    const TrilinosWrappers::SparseMatrix      &schur_approximation,
    const TrilinosWrappers::PreconditionAMG   &velocity_amg,
    const TrilinosWrappers::PreconditionILU   &schur_ilu)
    : system_matrix(system_matrix)
    , schur_approximation(schur_approximation)
    , velocity_amg(velocity_amg)
    , schur_ilu(schur_ilu)
  {}

  void
  StokesPreconditioner::vmult(
    TrilinosWrappers::MPI::BlockVector       &dst,
    const TrilinosWrappers::MPI::BlockVector &src) const
  {
    // Pressure: dst_p = -S̃⁻¹ src_p, to three digits; more buys nothing, as
    // S̃ is itself only an approximation of S.
    dst.block(1)               = 0.;
    const double pressure_norm = src.block(1).l2_norm();
    if (pressure_norm > 0.)
      {
        SolverControl control(1000, 1e-3 * pressure_norm);
        SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
        cg.solve(schur_approximation, dst.block(1), src.block(1), schur_ilu);
        dst.block(1) *= -1.;
      }

    // Velocity: dst_v = Ã⁻¹ (src_v - Bᵀ dst_p).
    if (velocity_rhs.size() != src.block(0).size())
      velocity_rhs.reinit(src.block(0));
    system_matrix.block(0, 1).vmult(velocity_rhs, dst.block(1));
    velocity_rhs.sadd(-1., src.block(0));
    velocity_amg.vmult(dst.block(0), velocity_rhs);
  }
} // namespace rbc_ifem

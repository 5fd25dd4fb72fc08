#include <rbc_ifem/fluid/stokes_preconditioner.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

namespace rbc_ifem
{
  namespace
  {
    /// M_p of a StokesOperator, as a matrix for SolverCG.
    struct PressureMass
    {
      const StokesOperator &stokes;
      void
      vmult(PressureVector &dst, const PressureVector &src) const
      {
        stokes.apply_pressure_mass(dst, src);
      }
    };
  } // namespace

  StokesPreconditioner::StokesPreconditioner(
    const StokesOperator    &stokes,
    const VelocityMultigrid &velocity_multigrid)
    : stokes(stokes)
    , velocity_multigrid(velocity_multigrid)
    , pressure_mass_diagonal(stokes.inverse_pressure_mass_diagonal())
  {}

  void
  StokesPreconditioner::vmult(FluidVector &dst, const FluidVector &src) const
  {
    // Pressure: dst_p = -S̃⁻¹ src_p, to two digits; more buys nothing, as
    // S̃ is itself only an approximation of S.
    dst.block(1)               = 0.;
    const double pressure_norm = src.block(1).l2_norm();
    if (pressure_norm > 0.)
      {
        SolverControl            control(100, 1e-2 * pressure_norm);
        SolverCG<PressureVector> cg(control);
        cg.solve(PressureMass{stokes},
                 dst.block(1),
                 src.block(1),
                 *pressure_mass_diagonal);
        dst.block(1) *= -1.;
      }

    // Velocity: dst_v = Ã⁻¹ (src_v - Bᵀ dst_p).
    if (velocity_rhs.size() != src.block(0).size())
      velocity_rhs.reinit(src.block(0));
    stokes.apply_pressure_gradient(velocity_rhs, dst.block(1));
    velocity_rhs.sadd(-1., src.block(0));
    velocity_multigrid.vmult(dst.block(0), velocity_rhs);
  }
} // namespace rbc_ifem

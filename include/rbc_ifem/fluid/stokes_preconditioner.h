#ifndef rbc_ifem_fluid_stokes_preconditioner_h
#define rbc_ifem_fluid_stokes_preconditioner_h

#include <rbc_ifem/fluid/fluid_vectors.h>
#include <rbc_ifem/fluid/stokes_operator.h>
#include <rbc_ifem/fluid/velocity_multigrid.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * The block upper-triangular preconditioner of the saddle-point system
   *
   *   [ A   Bᵀ ] [v]   [f]            P⁻¹ = [ Ã  Bᵀ ]⁻¹
   *   [ μB  0  ] [p] = [g],                 [ 0  -S̃ ]
   *
   * (Elman, Silvester, Wathen), with the continuity rows scaled by μ as
   * StokesOperator has them. Ã⁻¹ is one V-cycle of geometric multigrid on
   * the velocity block A = ρ/Δt M + μK (VelocityMultigrid); the Schur
   * complement S = μ B A⁻¹ Bᵀ is, for viscous flow, spectrally equivalent
   * to the pressure mass matrix and so to its diagonal: S̃ = diag(M_p).
   * The outer solver is FGMRES. Its iteration count does not grow with the
   * mesh (doc/fluid.md).
   */
  class StokesPreconditioner
  {
  public:
    StokesPreconditioner(const StokesOperator    &stokes,
                         const VelocityMultigrid &velocity_multigrid);

    void
    vmult(FluidVector &dst, const FluidVector &src) const;

  private:
    const StokesOperator                           &stokes;
    const VelocityMultigrid                        &velocity_multigrid;
    std::shared_ptr<DiagonalMatrix<PressureVector>> pressure_mass_diagonal;
    mutable VelocityVector                          velocity_rhs;
  };
} // namespace rbc_ifem

#endif

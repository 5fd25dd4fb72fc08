#ifndef rbc_ifem_fluid_stokes_preconditioner_h
#define rbc_ifem_fluid_stokes_preconditioner_h

#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The block upper-triangular preconditioner of the saddle-point system
   *
   *   [ A   Bᵀ ] [v]   [f]            P⁻¹ = [ Ã  Bᵀ ]⁻¹
   *   [ μB  0  ] [p] = [g],                 [ 0  -S̃ ]
   *
   * (Elman, Silvester, Wathen), with the continuity rows scaled by μ as
   * FluidProblem assembles them. Ã⁻¹ is one AMG V-cycle on the velocity
   * block A = ρ/Δt M + μK (+ convection); the Schur complement
   * S = μ B A⁻¹ Bᵀ is, for viscous flow, spectrally equivalent to the
   * pressure mass matrix, so S̃ = M_p, inverted by CG with ILU to a loose
   * tolerance.
   * Since that inner solve is not a fixed linear map, the outer solver is
   * FGMRES. With this preconditioner the iteration count does not grow with
   * the mesh (see benchmarks/).
   */
  class StokesPreconditioner
  {
  public:
    StokesPreconditioner(
      const TrilinosWrappers::BlockSparseMatrix &system_matrix,
      const TrilinosWrappers::SparseMatrix      &schur_approximation,
      const TrilinosWrappers::PreconditionAMG   &velocity_amg,
      const TrilinosWrappers::PreconditionILU   &schur_ilu);

    void
    vmult(TrilinosWrappers::MPI::BlockVector       &dst,
          const TrilinosWrappers::MPI::BlockVector &src) const;

  private:
    const TrilinosWrappers::BlockSparseMatrix &system_matrix;
    const TrilinosWrappers::SparseMatrix      &schur_approximation;
    const TrilinosWrappers::PreconditionAMG   &velocity_amg;
    const TrilinosWrappers::PreconditionILU   &schur_ilu;
    mutable TrilinosWrappers::MPI::Vector      velocity_rhs;
  };
} // namespace rbc_ifem

#endif

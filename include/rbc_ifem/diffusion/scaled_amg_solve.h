#ifndef rbc_ifem_diffusion_scaled_amg_solve_h
#define rbc_ifem_diffusion_scaled_amg_solve_h

#include <rbc_ifem/diffusion/diagonally_scaled.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <cmath>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The ML AMG of the cut-cell uptake solves (CutCellProblem), on
   * @p matrix of finite elements of degree @p degree: for an elliptic
   * problem, two smoothing sweeps, aggregation threshold 0.02, and the
   * coarsest level at most 500 rows. benchmarks/poisson_reference takes
   * the same, so that its yardstick is the same solver.
   */
  void
  initialize_uptake_amg(TrilinosWrappers::PreconditionAMG    &amg,
                        const TrilinosWrappers::SparseMatrix &matrix,
                        const unsigned int                    degree);

  /**
   * Solve @p matrix x = @p rhs by CG on the symmetrically Jacobi-scaled
   * system D K D (D⁻¹ x) = D b, D = diag(K)^(-1/2) (DiagonallyScaled:
   * every row weighs alike, whatever its material's αD), preconditioned by
   * @p amg seen through the same scaling. @p control comes with its
   * tolerance relative to |D b|, which is made absolute here (what a
   * NoConvergence then reports). @p x: the solution, in the layout of
   * @p rhs (without ghosts). SolverControl::NoConvergence if the
   * iterations run out.
   */
  void
  solve_scaled_cg(const TrilinosWrappers::SparseMatrix    &matrix,
                  const TrilinosWrappers::PreconditionAMG &amg,
                  const IndexSet                          &owned_dofs,
                  const TrilinosWrappers::MPI::Vector     &rhs,
                  TrilinosWrappers::MPI::Vector           &x,
                  SolverControl                           &control);

  /**
   * Solve @p matrix x = @p rhs with @p solver on the symmetrically
   * Jacobi-scaled system, preconditioned by @p preconditioner (of the
   * unscaled matrix) seen through the same scaling, as solve_scaled_cg()
   * does, started from @p x as given (in the layout of @p rhs). For
   * matrices that are not symmetric (GMRES) and other preconditioners.
   */
  template <typename Solver, typename Preconditioner>
  void
  solve_scaled(Solver                               &solver,
               const TrilinosWrappers::SparseMatrix &matrix,
               const Preconditioner                 &preconditioner,
               const IndexSet                       &owned_dofs,
               const TrilinosWrappers::MPI::Vector  &rhs,
               TrilinosWrappers::MPI::Vector        &x,
               SolverControl                        &control)
  {
    using Vector = TrilinosWrappers::MPI::Vector;
    // D = diag(A)^-1/2: every row O(1) on the diagonal.
    Vector scale(rhs), inverse_scale(rhs);
    for (const auto i : owned_dofs)
      {
        scale[i]         = 1. / std::sqrt(matrix.diag_element(i));
        inverse_scale[i] = 1. / scale[i];
      }
    scale.compress(VectorOperation::insert);
    inverse_scale.compress(VectorOperation::insert);

    Vector scaled_rhs(rhs);
    scaled_rhs.scale(scale);
    x.scale(inverse_scale);
    control.set_tolerance(control.tolerance() * scaled_rhs.l2_norm());
    solver.solve(
      DiagonallyScaled<TrilinosWrappers::SparseMatrix, Vector>(matrix, scale),
      x,
      scaled_rhs,
      DiagonallyScaled<Preconditioner, Vector>(preconditioner, inverse_scale));
    x.scale(scale);
  }
} // namespace rbc_ifem

#endif

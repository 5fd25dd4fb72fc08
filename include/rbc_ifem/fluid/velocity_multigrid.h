#ifndef rbc_ifem_fluid_velocity_multigrid_h
#define rbc_ifem_fluid_velocity_multigrid_h

#include <rbc_ifem/fluid/velocity_operator.h>

#include <deal.II/base/mg_level_object.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_transfer_global_coarsening.h>
#include <deal.II/multigrid/multigrid.h>

#include <functional>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  /**
   * One V-cycle of geometric multigrid for the velocity block A = (ρ/Δt) M
   * + μ K (VelocityOperator): the preconditioner of the velocity in the
   * Stokes solve (StokesPreconditioner), spectrally equivalent to A with a
   * bound independent of the mesh.
   *
   * Global coarsening (deal.II's MGTransferGlobalCoarsening): every level is
   * a mesh of its own, the next finer one with every cell coarsened once
   * where it can be, down to the capillary's coarse mesh; so levels have
   * hanging nodes where the fine mesh has them, and a locally refined band
   * costs no special treatment. On each level Q2 with the same boundary
   * conditions; Chebyshev smoothing of degree 2 around the inverse
   * diagonal (eigenvalues estimated once per coefficient change), on the
   * coarsest mesh one V-cycle of algebraic multigrid (Trilinos ML), each
   * rank its part.
   */
  class VelocityMultigrid
  {
  public:
    /// Fill @p constraints (reinit'ed here) with the homogeneous
    /// constraints of the velocity on @p dof_handler.
    using ConstraintMaker =
      std::function<void(const DoFHandler<3> &, AffineConstraints<double> &)>;

    /**
     * @p coarser_meshes: the levels below the fine mesh, coarsest first
     * (each the next one coarsened once). The finest level is the velocity
     * of @p fine_matrix_free (DoF index @p fine_dof_index, constraints
     * @p fine_constraints, those of the MatrixFree). @p make_constraints
     * gives every coarser level its boundary conditions. The meshes, the
     * mapping and the constraints must outlive this object.
     */
    VelocityMultigrid(
      const std::vector<std::shared_ptr<const Triangulation<3>>>
                                                  &coarser_meshes,
      const Mapping<3>                            &mapping,
      std::shared_ptr<const MatrixFree<3, double>> fine_matrix_free,
      const unsigned int                           fine_dof_index,
      const AffineConstraints<double>             &fine_constraints,
      const ConstraintMaker                       &make_constraints);

    ~VelocityMultigrid();

    /**
     * Set the coefficients ρ/Δt and μ on every level, and rebuild what
     * depends on them: the smoothers' diagonals and eigenvalue estimates,
     * the coarse matrix and its factorisation.
     */
    void
    set_coefficients(const double mass_factor, const double viscosity);

    /**
     * Add to each level's A the term of @p terms (one per level, coarsest
     * first; its diagonal in @p diagonals), and rebuild the smoothers. The
     * coarsest level's solve keeps A alone.
     */
    void
    set_added_terms(const std::vector<VelocityOperator::AddedTerm> &terms,
                    const std::vector<VelocityVector>              &diagonals);

    /// The DoFs of @p level (0 the coarsest, n_levels() - 1 the fine one).
    const DoFHandler<3> &
    level_dof_handler(unsigned int level) const;

    /// The homogeneous velocity constraints of @p level.
    const AffineConstraints<double> &
    level_zero_constraints(unsigned int level) const;

    /// @p v with the layout of @p level's operator.
    void
    initialize_level_vector(unsigned int level, VelocityVector &v) const;

    /// dst = one V-cycle applied to src (vectors of the fine operator).
    void
    vmult(VelocityVector &dst, const VelocityVector &src) const;

    /// The number of levels, the fine one included.
    unsigned int
    n_levels() const;

    /// The DoFs of every level, coarsest first.
    std::vector<types::global_dof_index>
    n_dofs_per_level() const;

  private:
    using Transfer = MGTransferGlobalCoarsening<3, VelocityVector>;
    using Smoother = PreconditionChebyshev<VelocityOperator,
                                           VelocityVector,
                                           DiagonalMatrix<VelocityVector>>;
    class CoarseSolver;

    /// The smoothers (from the operators as they are now, their largest
    /// eigenvalues estimated by @p eigenvalue_iterations CG steps) and the
    /// cycle.
    void
    build_cycle(unsigned int eigenvalue_iterations);

    /// The levels' DoFs and constraints; the finest level's are the
    /// MatrixFree's, pointed to here.
    MGLevelObject<DoFHandler<3>>                         dof_handlers;
    MGLevelObject<AffineConstraints<double>>             constraints;
    MGLevelObject<const DoFHandler<3> *>                 level_dofs;
    MGLevelObject<const AffineConstraints<double> *>     level_constraints;
    MGLevelObject<std::unique_ptr<VelocityOperator>>     operators;
    MGLevelObject<MGTwoLevelTransfer<3, VelocityVector>> transfers;
    std::unique_ptr<Transfer>                            transfer;
    MGSmootherPrecondition<VelocityOperator, Smoother, VelocityVector> smoother;
    std::unique_ptr<CoarseSolver>                                      coarse;
    std::unique_ptr<mg::Matrix<VelocityVector>>                  level_matrices;
    std::unique_ptr<Multigrid<VelocityVector>>                   multigrid;
    std::unique_ptr<PreconditionMG<3, VelocityVector, Transfer>> v_cycle;
  };
} // namespace rbc_ifem

#endif

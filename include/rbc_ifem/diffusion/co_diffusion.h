#ifndef rbc_ifem_diffusion_co_diffusion_h
#define rbc_ifem_diffusion_co_diffusion_h

#include <rbc_ifem/base/field_data.h>
#include <rbc_ifem/diffusion/diffusion_solver.h>
#include <rbc_ifem/diffusion/parameters.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_block_sparse_matrix.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The membranes' cells are finer than the diffusion mesh around them:
   * the multiplier then violates the inf-sup condition of the saddle point
   * problem (with membrane cells 1.7 times smaller FGMRES no longer
   * converges). The caller, who knows which parameters made the meshes,
   * turns it into an InputError.
   */
  class MembranesFinerThanMesh : public std::runtime_error
  {
  public:
    MembranesFinerThanMesh(const double membrane_cell_size,
                           const double volume_cell_size);

    const double membrane_cell_size; ///< mean membrane cell size [µm]
    const double volume_cell_size;   ///< mean diffusion cell size there [µm]
  };

  /**
   * Steady CO diffusion into the red cells, the paper's Section 3.2:
   *
   *   -∇·(αD ∇P) = 0 in the volume mesh,  P = P_A on one boundary id,
   *   no flux elsewhere on the boundary,  P = 0 on every membrane.
   *
   * The membranes (Triangulation<2,3>) do not conform to the volume mesh.
   * As in deal.II's step-60, P = 0 is imposed weakly through a Lagrange
   * multiplier λ in FE_Q<2,3>(1) on each membrane:
   *
   *   (αD ∇P, ∇q) + (λ, q)_Γ = 0    for all q,
   *   (μ, P)_Γ               = 0    for all μ.
   *
   * λ is the jump of αD ∂P/∂n across the membrane (n out of the cell): the
   * CO flux density into the cell [µm³ of CO per µm² and s], so the flux map
   * and DM come out of the solve. Inside a cell P ≈ 0; what little
   * gradient the discrete field keeps there tends to zero with the mesh
   * size, which the analytic checks in tests/ measure.
   *
   * The saddle point system is solved by FGMRES with an augmented
   * Lagrangian block-triangular preconditioner (Benzi & Olshanskii, SIAM J.
   * Sci. Comput. 28, 2006): the P block is A + γ Bᵀ W B (W the inverse
   * lumped membrane mass), which leaves the solution unchanged because
   * B P = 0 there, and makes the Schur complement of the multiplier close to
   * (γ W)⁻¹, so that one diagonal scaling preconditions it independently of
   * the mesh size; the P block gets one AMG V-cycle per iteration.
   *
   * The volume mesh is a parallel::shared::Triangulation: every rank knows
   * every cell, so every rank can locate every membrane point.
   */
  class CODiffusion : public DiffusionSolver
  {
  public:
    /**
     * @p permeability maps a material id of the volume mesh to αD
     * [µm²/(s Torr)]; @p pressure_boundary is the boundary id where
     * P = P_A holds. With a @p period along x (a periodic capillary
     * segment) P is periodic between the end faces
     * (DiffusionBoundary::inlet_end and outlet_end), and each membrane
     * point is located where it lies in the segment (wrap_into_segment()),
     * so a cell may straddle the ends.
     */
    CODiffusion(const DiffusionParameters                 &parameters,
                const std::function<double(unsigned int)> &permeability,
                const types::boundary_id                   pressure_boundary,
                const MPI_Comm                             communicator,
                TimerOutput                               &timer,
                const std::optional<double> &period = std::nullopt);
    ~CODiffusion() override;

    /**
     * Distribute the DoFs of P on @p mesh and of λ on @p membranes, locate
     * the membranes' quadrature points in @p mesh, build the sparsity
     * patterns. Throws InputError if a membrane leaves the mesh,
     * MembranesFinerThanMesh if the membranes are too fine for it. @p mesh
     * must be a parallel::shared::Triangulation: every rank locates every
     * membrane point in it. Both must outlive this object.
     */
    void
    setup(const parallel::TriangulationBase<3> &mesh,
          const MembraneSurfaces               &membranes);

    void
    assemble() override;

    /// Solve for P and λ; throws SolverFailure if FGMRES does not converge.
    void
    solve() override;

    /// DM = total_flow() / P_A [µm³ s⁻¹ Torr⁻¹].
    double
    dm_total() const;

    types::global_dof_index
    n_pressure_dofs() const;
    types::global_dof_index
    n_multiplier_dofs() const;
    /// P and λ.
    types::global_dof_index
    n_dofs() const override;

    /**
     * The flux map is λ itself: "co_flux" = λ, "co_flux_vector" = -λ n (n
     * out of the cell).
     */
    OutputFiles
    write_output(const std::string &directory,
                 const std::string &name,
                 const unsigned int counter    = 0,
                 const FieldData   &field_data = {}) const override;

  private:
    struct CouplingData;

    void
    setup_multipliers();
    /// The quadrature points of the multipliers' cells (wrapped into a
    /// periodic segment), their JxW and DoFs stored in coupling.
    std::vector<Point<3>>
    membrane_quadrature_points();
    /// Find the volume cell of every membrane quadrature point.
    void
    locate_membrane_points();
    /// Throw MembranesFinerThanMesh if the multipliers' cells are finer
    /// than the volume mesh around them; set the constraint's scale.
    void
    check_inf_sup();
    void
    setup_matrices();
    void
    assemble_stiffness();
    void
    assemble_coupling();
    void
    assemble_augmentation();
    void
    compute_flows();

    const DiffusionParameters                 parameters;
    const std::function<double(unsigned int)> permeability;
    const types::boundary_id                  pressure_boundary;
    const std::optional<double>               period;
    const MPI_Comm                            communicator;
    TimerOutput                              &timer;

    const parallel::shared::Triangulation<3> *mesh = nullptr;
    FE_Q<3>                                   fe;
    MappingQ<3>                               mapping;
    DoFHandler<3>                             dof_handler;
    IndexSet                                  owned_dofs;
    AffineConstraints<double>                 constraints;

    std::vector<const Triangulation<2, 3> *>       membranes;
    const MappingQ<2, 3>                          *membrane_mapping = nullptr;
    FE_Q<2, 3>                                     multiplier_fe;
    std::vector<std::unique_ptr<DoFHandler<2, 3>>> multiplier_dof_handlers;
    std::vector<types::global_dof_index>           multiplier_offsets;
    IndexSet                                       owned_multipliers;
    std::unique_ptr<CouplingData>                  coupling;

    /// Scale of the constraint rows, αD_plasma / h_Γ, so both rows of the
    /// system have the units of the P equation (see doc/diffusion.md).
    double constraint_scale = 1.;

    TrilinosWrappers::SparseMatrix stiffness;       ///< A + γ Bᵀ W B
    TrilinosWrappers::SparseMatrix coupling_matrix; ///< B, λ rows × P columns
    SparsityPattern                coupling_sparsity;
    SparseMatrix<double> full_coupling_matrix; ///< all of B, every rank
    TrilinosWrappers::MPI::Vector      multiplier_weights; ///< γ W
    TrilinosWrappers::PreconditionAMG  amg;
    TrilinosWrappers::MPI::BlockVector solution;
    TrilinosWrappers::MPI::BlockVector rhs;

    Vector<double> multiplier_mass;   ///< ∫ μ_i dA, every i, every rank
    Vector<double> multiplier_values; ///< λ, all of it, on every rank
  };
} // namespace rbc_ifem

#endif

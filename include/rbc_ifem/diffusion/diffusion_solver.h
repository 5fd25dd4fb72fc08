#ifndef rbc_ifem_diffusion_diffusion_solver_h
#define rbc_ifem_diffusion_diffusion_solver_h

#include <rbc_ifem/base/field_data.h>
#include <rbc_ifem/base/solver_failure.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * A steady CO uptake solve, the paper's Section 3.2: -∇·(αD∇P) = 0 in
   * the diffusion mesh, P = P_A on its alveolar surface, and at the red
   * cell membranes either P = 0 (the membrane sink, whose flow per P_A is
   * DM: CODiffusion with a Lagrange multiplier, CutCellDiffusion on cut
   * cells) or CO going on into the cells and bound there (CutCellReaction,
   * whose flow per P_A is DL). The membranes do not conform to the mesh.
   * What comes out is the same for every problem: the CO flow into each
   * membrane, the flow through the alveolar surface (which must equal their
   * sum), the P field and the flux map on the membranes. Each problem sets
   * itself up from what it needs (a mesh and the membranes, or the cut-cell
   * geometry), then assemble() and solve().
   */
  class DiffusionSolver
  {
  public:
    virtual ~DiffusionSolver() = default;

    /// Assemble the matrices and build the preconditioner.
    virtual void
    assemble() = 0;

    /// Solve; throws SolverFailure if the linear solver does not converge.
    virtual void
    solve() = 0;

    /**
     * CO flow into each membrane [µm³ s⁻¹, volume of CO at STPD]: αD is in
     * µm²/(s Torr) and P in Torr.
     */
    const std::vector<double> &
    membrane_flows() const;

    /// Total CO flow into all membranes [µm³ s⁻¹].
    double
    total_flow() const;

    /**
     * CO flow out through the pressure boundary, computed from the residual
     * of the P equation on the boundary DoFs. It equals total_flow() to
     * solver tolerance (conservation).
     */
    double
    boundary_flow() const;

    /// Unknowns of the discrete problem (P, and λ if the method has one).
    virtual types::global_dof_index
    n_dofs() const = 0;

    /// Iterations of the last linear solve.
    unsigned int
    n_iterations() const;

    /// The files of one write_output().
    struct OutputFiles
    {
      std::string pressure;  ///< NAME_CCCC.pvtu
      std::string membranes; ///< NAME_membranes_CCCC.vtu
    };

    /**
     * P as NAME_CCCC.pvtu (+ one piece per rank) and the membranes as
     * NAME_membranes_CCCC.vtu with the flux density into them [µm³ of CO
     * per µm² and s] as a scalar "co_flux" and as the vector
     * "co_flux_vector" (pointing into the cell: the direction CO moves, the
     * paper's Fig. 4f); CCCC is @p counter. The caller lists the files in
     * its .pvd records. Every file carries @p field_data.
     */
    virtual OutputFiles
    write_output(const std::string &directory,
                 const std::string &name,
                 const unsigned int counter    = 0,
                 const FieldData   &field_data = {}) const = 0;

  protected:
    explicit DiffusionSolver(const double alveolar_pressure);

    /// total_flow() / P_A [µm³ s⁻¹ Torr⁻¹]: DM of a membrane sink, DL of
    /// the reaction; each problem names it so.
    double
    flow_per_pressure() const;

    /**
     * The failure of the linear solver @p solver (its name in the message)
     * that stopped as @p e says, short of @p tolerance, with @p advice on
     * what to change.
     */
    static SolverFailure
    no_convergence(const std::string                  &solver,
                   const SolverControl::NoConvergence &e,
                   const double                        tolerance,
                   const std::string                  &advice);

    /**
     * The flow through boundary @p boundary: Σ over its DoFs j of
     * a(P, φ_j) = ∫ αD ∇P · ∇φ_j, the residual the Dirichlet values hold
     * up. @p P must have ghost values; @p dof_handler may be an hp one
     * (cells without DoFs are skipped), and P its first component.
     */
    static double
    flow_through_boundary(
      const DoFHandler<3>                       &dof_handler,
      const Mapping<3>                          &mapping,
      const TrilinosWrappers::MPI::Vector       &P,
      const types::boundary_id                   boundary,
      const std::function<double(unsigned int)> &permeability,
      const MPI_Comm                             communicator);

    /**
     * The constraints of P on @p dof_handler (an hp one too, P its first
     * component): hanging nodes, the DoFs @p zero_dofs held at zero (those
     * a hanging node does not already constrain), P = @p pressure on
     * boundary @p pressure_boundary, and with a @p period P periodic between
     * the end faces.
     */
    static void
    make_pressure_constraints(const DoFHandler<3>         &dof_handler,
                              const Mapping<3>            &mapping,
                              const types::boundary_id     pressure_boundary,
                              const double                 pressure,
                              const std::optional<double> &period,
                              AffineConstraints<double>   &constraints,
                              const IndexSet              &zero_dofs = {});

    /**
     * Write the P field of @p data_out (patches built) as NAME_CCCC.pvtu and
     * the flux density @p flux (nodal, one vector per membrane, in
     * FE_Q<2,3>(1) on @p dof_handlers) as "co_flux" and "co_flux_vector" on
     * @p membranes as NAME_membranes_CCCC.vtu, the flux map there as
     * @p flux_name (and FLUX_NAME_vector, the flux vector).
     */
    static OutputFiles
    write_fields(
      const DataOut<3>                                     &data_out,
      const std::vector<const Triangulation<2, 3> *>       &membranes,
      const MappingQ<2, 3>                                 &mapping,
      const std::vector<std::unique_ptr<DoFHandler<2, 3>>> &dof_handlers,
      const std::vector<Vector<double>>                    &flux,
      const std::string                                    &directory,
      const std::string                                    &name,
      const unsigned int                                    counter,
      const MPI_Comm                                        communicator,
      const FieldData                                      &field_data,
      const std::string                                    &flux_name);

    std::vector<double> flows;              ///< into each membrane
    double              alveolar_flow = 0.; ///< out of the P_A boundary
    unsigned int        iterations    = 0;

  private:
    double alveolar_pressure;
  };
} // namespace rbc_ifem

#endif

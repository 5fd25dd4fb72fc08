#ifndef rbc_ifem_diffusion_cut_cell_oxygen_h
#define rbc_ifem_diffusion_cut_cell_oxygen_h

#include <rbc_ifem/diffusion/binding_preconditioner.h>
#include <rbc_ifem/diffusion/cut_cell_problem.h>
#include <rbc_ifem/diffusion/oxygen_parameters.h>

#include <deal.II/numerics/data_postprocessor.h>

#include <array>
#include <memory>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  /**
   * O2 and hemoglobin over time on cut cells, the red cells held where
   * the geometry has them (OxygenParameters has the model):
   *
   *   α ∂P/∂t = ∇·(αD ∇P)                 in the plasma, wall and gas,
   *   α_c ∂P/∂t = ∇·(α_cD_c ∇P) − C q,  C ∂S/∂t = ∇·(C D_Hb ∇S) + C q
   *                                        in the cells,
   *
   * P and its flux continuous across the membranes (the Nitsche terms of
   * CutCellReaction, Hansbo's weights w₀ = α_cD_c/(αD + α_cD_c)), no flux
   * of S through them, P = P_A on the alveolar surface.
   *
   * The fields, one FESystem: P₀ in the plasma (field 0), P₁ of the red
   * cells of colour c (1 + c) and their S (1 + n_colours + c), each with
   * its ghost penalty (CutCellReaction says why cells of one colour must
   * not touch).
   *
   * The capacities (α for P, C for S) and the binding are lumped to the
   * nodes: each mesh cell's part of each region lumped by its mass
   * matrix's diagonal scaled to the part's volume (HRZ, positive on cut
   * cells, where row sums need not be), summed to the DoFs through the
   * constraints. The binding is then a pair of ODEs at each node inside
   * a cell, and the O2 the scheme conserves is Σ_i c_i u_i exactly.
   *
   * In time, BDF2 with the binding implicit, by Newton's method; each
   * Newton iteration is one GMRES solve, preconditioned by
   * BindingPreconditioner (set up once per step). Strang splitting of the
   * binding from the diffusion was tried and fails: P relaxes to
   * equilibrium with S within tens of µs ((C/α_c) q_P ~ 3e4 s⁻¹ at
   * 40 Torr), so between the binding's half steps the cell's P fills up
   * as if nothing bound it, and the uptake per step was fixed by the
   * cytoplasm's capacity, not by the step (10 steps took up half what 20
   * did). Every part conserves O2: the change of Σ c_i u_i per step is
   * the flow through the alveolar surface (the residual of the rows held
   * at P_A, integrated by the same rule) to the solver's tolerance, and
   * that of one cell is the Nitsche flux through its membrane.
   */
  class CutCellOxygen : public CutCellProblem
  {
  public:
    /// What the cells hold at one time.
    struct CellState
    {
      double volume;     ///< the cell's lumped volume [µm³]
      double oxygen;     ///< ∫ (α_c P + C S) [µm³ O2]
      double saturation; ///< the volume mean of S
      double pressure;   ///< the volume mean of P [Torr]
    };

    /// The O2 in the whole mesh, by kind [µm³ O2].
    struct Amounts
    {
      double dissolved; ///< ∫ α P, plasma, wall, gas and cells
      double bound;     ///< ∫ C S
    };

    /**
     * Set up the problem of @p oxygen, with the degree, penalties and
     * solver tolerances of @p parameters, and the binding @p binding
     * (kept by reference), on @p geometry (built with separate insides),
     * P = P_A on boundary @p pressure_boundary.
     */
    CutCellOxygen(const CutCellGeometry     &geometry,
                  const DiffusionParameters &parameters,
                  const OxygenParameters    &oxygen,
                  const OxygenBinding       &binding,
                  const types::boundary_id   pressure_boundary,
                  TimerOutput               &timer);

    /// The operator, the capacities and the node pairs of the binding.
    void
    assemble() override;

    /**
     * Start at time 0 with P = @p pressure everywhere (but P_A on the
     * alveolar surface) and S in equilibrium with it.
     */
    void
    start(const double pressure);

    /// Not used: a problem in time advances (advance()).
    void
    solve() override;

    /**
     * One step of @p time_step [s]: BDF2 for a step of this length after
     * the last one's (Bdf2; BDF1 the first step after start()). Throws
     * SolverFailure if Newton's method or GMRES does not converge or the fields
     * are not finite.
     */
    void
    advance(const double time_step);

    /**
     * Solve the step of @p time_step [s] as advance() does, but keep it
     * aside until accept_step() (a step not accepted is tried again
     * shorter). Returns an estimate of the step's local error (Bdf2Error),
     * the root mean square over the free DoFs of P's relative to P_A and
     * S's; zero for the first two steps, which have no estimate. A step
     * that throws (as advance()) leaves the fields as they were, so that
     * it can be tried again shorter.
     */
    double
    try_step(const double time_step);

    /// Make the step last tried the fields.
    void
    accept_step();

    /// The time of the fields [s].
    double
    time() const;

    /// Each red cell's state (in the order of the membranes), on all ranks.
    std::vector<CellState>
    cell_states() const;

    /// The O2 in the mesh, on all ranks.
    Amounts
    amounts() const;

    /// The O2 that entered through the alveolar surface since start(),
    /// integrated as the scheme does [µm³ O2].
    double
    wall_oxygen() const;

    /// Compute the O2 flux into the membranes for the output's flux map
    /// (write_output() writes it; collective).
    void
    update_flux_map();

    /// The Newton iterations and the GMRES iterations of the last step.
    std::pair<unsigned int, unsigned int>
    last_iterations() const;

  protected:
    /// Plasma, and the P₁ and S of the red cell the cell reaches into.
    std::vector<unsigned int>
    fields_on(const Triangulation<3>::cell_iterator &cell) const override;

    /// Plasma and P₁: S does not cross the membranes.
    std::vector<unsigned int>
    pressure_fields_on(
      const Triangulation<3>::cell_iterator &cell) const override;

    NonMatching::RegionUpdateFlags
    assembly_flags() const override;

    void
    add_cell_terms(const NonMatching::FEValues<3>            &values,
                   const DoFHandler<3>::active_cell_iterator &cell,
                   const CutCellShapes                       &shapes,
                   FullMatrix<double> &matrix) const override;

    MembraneCoupling
    membrane_coupling(
      const DoFHandler<3>::active_cell_iterator &cell) const override;

    /// α_cD_c for P₁, C D_Hb for S (the ghost penalty's weights).
    double
    field_permeability(
      const unsigned int                         field,
      const DoFHandler<3>::active_cell_iterator &cell) const override;

    /// "o2_flux": the O2 flux into the cells [µm³ O2 µm⁻² s⁻¹].
    std::string
    flux_name() const override;

    /// "po2" in the plasma, "po2_cell" and "saturation" in the cells.
    void
    add_pressure_fields(DataOut<3> &data_out) const override;

  private:
    /// The lumped capacities of each field of @p cell's region parts,
    /// per local DoF (α or C times the lumped volume).
    Vector<double>
    lumped_capacities(const NonMatching::FEValues<3>            &values,
                      const DoFHandler<3>::active_cell_iterator &cell) const;
    /// Add the capacities @p local of a cell's DoFs @p dofs to @p global,
    /// those of constrained DoFs to the DoFs they hang on, all positive.
    void
    add_to_free_dofs(const Vector<double>                       &local,
                     const std::vector<types::global_dof_index> &dofs,
                     TrilinosWrappers::MPI::Vector              &global) const;
    /// The binding_nodes of this rank.
    void
    find_binding_pairs();
    /// The flow in through the alveolar surface at the solution's P
    /// [µm³ O2/s]: the residual of the rows held at P_A.
    double
    alveolar_inflow() const;
    /// step_matrix = the operator + @p sigma_over_dt c, without the binding.
    void
    set_up_step_matrix(const double sigma_over_dt);
    /**
     * Newton's method for the fields of the step whose capacity term is
     * @p sigma_over_dt c u − @p history, from @p start: each iteration
     * one GMRES solve with BindingPreconditioner, set up once per step,
     * that takes the residual down by GMRES's tolerance, until the
     * residual is within newton_tolerance times GMRES's tolerance of the
     * one at the start (at least one solve, whatever the start) or at
     * round-off; then conserve(). Leaves the fields in solution.
     */
    void
    solve_step(const double                         sigma_over_dt,
               const TrilinosWrappers::MPI::Vector &history,
               const TrilinosWrappers::MPI::Vector &start);
    /**
     * Shift the free DoFs of @p u alike so that the sum of the step's
     * @p residual at @p u (the O2 the step's balance misses by) is zero,
     * whatever GMRES's tolerance, and distribute.
     */
    void
    conserve(const TrilinosWrappers::MPI::Vector &residual,
             TrilinosWrappers::MPI::Vector       &u) const;
    /// free_dofs and error_weights, for the constraints and P_A.
    void
    set_free_dofs();
    /// try_step()'s estimate for the step @p time_step in solution.
    double
    local_error(const double time_step) const;
    /// One GMRES solve of step_matrix @p u = @p b from @p u (its
    /// constrained DoFs zero) to @p tolerance relative to |D b|,
    /// distributed; returns the iterations.
    unsigned int
    solve_linear(const TrilinosWrappers::MPI::Vector &b,
                 TrilinosWrappers::MPI::Vector       &u,
                 const double                         tolerance);
    /// |D v|, D = diag(step_matrix)^-1/2: the norm of solve_scaled().
    double
    scaled_norm(const TrilinosWrappers::MPI::Vector &v) const;
    /**
     * The binding w q at each node (w = C times the node's volume),
     * linearised at @p u, q ≈ q₀ + q_P P + q_S S: − w q₀ into P₁'s row of
     * @p b and + w q₀ into S's, its Jacobian into step_matrix (in place
     * of the last one).
     */
    void
    set_binding(const TrilinosWrappers::MPI::Vector &u,
                TrilinosWrappers::MPI::Vector       &b);
    /// The (P₁, S) DoFs of the binding_nodes.
    std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
    binding_pairs() const;

    const OxygenParameters oxygen;
    const OxygenBinding   &binding;
    const unsigned int     n_colours;

    /// c_i: the lumped capacity of each owned DoF [µm³ O2 / Torr or / 1].
    TrilinosWrappers::MPI::Vector capacity;
    /// The DoFs held at P_A on the alveolar surface (this rank's cells).
    IndexSet held_dofs;
    /// A node inside a red cell: its P₁ and S DoFs (S's owned here) and
    /// the red cell (membrane index).
    struct BindingNode
    {
      types::global_dof_index pressure, saturation;
      unsigned int            cell;
      /// The binding's share of step_matrix's (P₁,P₁), (P₁,S), (S,P₁),
      /// (S,S).
      std::array<double, 4> binding;
    };
    std::vector<BindingNode> binding_nodes;
    /// The fields at the last three steps, owned (solution has the step
    /// being tried, with ghosts).
    TrilinosWrappers::MPI::Vector fields, older_fields, oldest_fields;
    /// The operator with the capacities of the step and the binding.
    TrilinosWrappers::SparseMatrix step_matrix;
    /// The σ/Δt step_matrix holds (zero: none yet).
    double step_sigma_over_dt = 0.;
    /// 1 on the owned DoFs that are not constrained, and 1ᵀ step_matrix 1
    /// over them (for conserve()).
    TrilinosWrappers::MPI::Vector free_dofs;
    double                        free_row_sum = 0.;
    /// 1/P_A on the free DoFs of P, 1 on those of S, zero elsewhere.
    TrilinosWrappers::MPI::Vector error_weights;
    BindingPreconditioner         preconditioner;
    /// Newton stops, after at least one solve, when the residual is this
    /// times GMRES's tolerance times the step's first, or this times
    /// round_off |D b| (a start already at round-off takes no GMRES
    /// iteration).
    static constexpr double       newton_tolerance      = 10.;
    static constexpr unsigned int max_newton_iterations = 20;
    /// Residuals below this times |D b| are round-off: GMRES is asked for
    /// no less (asked for 7e-18, it stalled at 3.6e-15).
    static constexpr double round_off = 1e-12;

    /// The time, the last two steps, and the step being tried [s].
    double current_time = 0., last_step = 0., older_step = 0., next_step = 0.;
    unsigned int n_steps = 0;
    /// The wall's O2 (since start()) at the last two steps and the step
    /// being tried [µm³ O2].
    double       wall = 0., old_wall = 0., next_wall = 0.;
    unsigned int newton_iterations = 0, linear_iterations = 0;

    /// The fields for the output (DataOut keeps references to them).
    std::vector<std::unique_ptr<const DataPostprocessor<3>>> output_fields;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_fluid_fluid_problem_h
#define rbc_ifem_fluid_fluid_problem_h

#include <rbc_ifem/base/field_data.h>
#include <rbc_ifem/fluid/flow_drive.h>
#include <rbc_ifem/fluid/fluid_vectors.h>
#include <rbc_ifem/fluid/parameters.h>
#include <rbc_ifem/geometry/cell_records.h>

#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/fe/mapping_q_cache.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// Integral quantities of a flow field, as flow.csv reports them.
  struct FlowMeasures
  {
    /// ∫ v·n over the outlet [µm³/s], v the velocity the frame sees
    double flow_rate = 0.;
    /// The same in the laboratory, ∫ (v + V e_x)·n, V the frame velocity
    double lab_flow_rate = 0.;
    /// Mean inlet minus mean outlet pressure [pN/µm²]; in a periodic
    /// segment the drop G L that the pressure gradient imposes.
    double pressure_drop = 0.;
    double max_velocity  = 0.; ///< largest |v| at quadrature points [µm/s]
    double divergence_l2 = 0.; ///< ‖∇·v‖ in L2 [µm^1.5/s]
  };

  /// What one time step took.
  struct StepReport
  {
    unsigned int        newton_iterations = 0;
    unsigned int        linear_iterations = 0; ///< FGMRES, summed over Newton
    std::vector<double> residuals; ///< ‖R‖ before each Newton update (and,
                                   ///< Navier-Stokes, after the last)
    /// ‖R‖ at the end of the step: for Stokes FGMRES's final residual (the
    /// problem is linear), for Navier-Stokes the last Newton residual.
    double final_residual = 0.;
  };

  /**
   * What a restart needs to continue a FluidProblem besides the solution's
   * values (FluidProblem::cell_values(), kept per cell so that any number
   * of ranks can read them): the frame velocity, the residual scale the
   * solver's tolerance refers to, and whether the values hold the solution
   * one step earlier too. The same on every rank.
   */
  struct FluidState
  {
    /// Whether there is a solution one step earlier, for the extrapolated
    /// first guess (not before the first step).
    bool                    has_earlier    = false;
    double                  frame_velocity = 0.;
    double                  residual_scale = 0.;
    types::global_dof_index n_dofs = 0; ///< of the problem that wrote it

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &has_earlier &frame_velocity &residual_scale &n_dofs;
    }
  };

  class StokesOperator;
  class StokesPreconditioner;
  class VelocityMultigrid;

  /**
   * The plasma flow in the capillary lumen (doc/design.md, Section 2): velocity
   * v and pressure p in Taylor-Hood Q2-Q1 (one DoFHandler each) on a mesh
   * from create_fluid_mesh(), with a quadratic mapping for the curved wall.
   *
   * Each time step is backward Euler for
   *
   *   ρ (v - vⁿ)/Δt [+ ρ (v·∇)v] - μΔv + ∇p = f,   ∇·v = 0,
   *
   * with the continuity equation multiplied by μ, so that both rows of the
   * residual have the same units (pN·µm) and the solver's relative tolerance
   * weighs them alike (without it, ∇·v rows are ~10³ times larger than the
   * momentum rows in these units and the pressure converges poorly),
   * solved by Newton's method on the residual R(v, p): the right-hand side
   * of every linear solve is the residual, and updates satisfy homogeneous
   * constraints. Every operator is matrix-free (StokesOperator): the
   * residual is one pass over the cells with sum factorisation, not an
   * assembly. The linear solver is FGMRES with StokesPreconditioner:
   * geometric multigrid on the velocity (VelocityMultigrid, on the meshes
   * of a global coarsening of this one), the pressure mass matrix for the
   * Schur complement. In Stokes mode the Jacobian is the Stokes operator
   * and a step is one residual and one FGMRES solve, which solves the
   * linear problem exactly; Navier-Stokes mode linearises the convection
   * about the Newton iterate and keeps the Stokes multigrid as the
   * velocity preconditioner (Re ≪ 1 in a capillary).
   *
   * Boundary conditions (FlowDrive): in the capillary no slip on the wall,
   * the Poiseuille profile of mean speed ū at the inlet, both shifted by
   * -U_frame e_x in a frame moving with U_frame; in the shear box simple
   * shear on the walls; in a periodic capillary no slip on the wall, v and
   * p periodic along x, and the drive's pressure gradient as a body force.
   * On the open boundaries (the capillary's outlet, the
   * box's ends) the do-nothing condition μ ∂v/∂n - p n = 0
   * (the gradient form of the viscous term; with constant μ and ∇·v = 0 it
   * equals ∇·(2με(v)) inside the domain, and it admits the fully developed
   * Poiseuille flow with p = 0 at the outlet).
   *
   * The membrane forces of the immersed method enter through
   * set_body_force(): a load vector f_J = Σ_I F_I φ_J(x_I) of the velocity
   * space.
   */
  class FluidProblem
  {
  public:
    /**
     * The flow on @p triangulation (serial, parallel::shared or fully
     * distributed; it must outlive the problem).
     */
    FluidProblem(const Triangulation<3> &triangulation,
                 const FluidParameters  &parameters,
                 const FlowDrive        &drive,
                 const double            time_step,
                 TimerOutput            &timer);

    ~FluidProblem();

    /**
     * Distribute DoFs, build constraints, the operators and the multigrid
     * hierarchy on @p coarser_meshes, the global coarsening of the mesh
     * (create_distributed_mesh_hierarchy()); without them, for a serial or
     * shared mesh, global_coarsening_sequence() makes them.
     */
    void
    setup(const std::vector<std::shared_ptr<const Triangulation<3>>>
            &coarser_meshes = {});

    /**
     * Change the time step Δt [s]. The velocity operator and its multigrid
     * smoothers depend on it, so they are updated (only if Δt changed).
     */
    void
    set_time_step(const double time_step);

    /**
     * Change the frame velocity U_frame [µm/s]: the boundary values change
     * at the next step, and the current field is seen from the new frame
     * (v - ΔU e_x, a Galilean change), so the time derivative holds no
     * spurious acceleration.
     */
    void
    set_frame_velocity(const double frame_velocity);

    double
    get_frame_velocity() const;

    /// What a restart needs besides cell_values(): the same on every rank.
    FluidState
    state() const;

    /**
     * The solution's values on each locally owned cell, velocity then
     * pressure in the cells' DoF order, and after them the same of the
     * solution one step earlier if there is one (FluidState::has_earlier).
     */
    CellRecords
    cell_values() const;

    /**
     * Continue from @p state and @p owned, the cell_values() of a problem on
     * the same mesh (partitioned in any way), for the locally owned cells
     * here (CellRecords::to_owners()).
     */
    void
    set_state(const FluidState &state, const CellRecords &owned);

    /// @p v with the layout of the velocity block: owned entries and the
    /// ghosts a rank's cells touch. Load vectors are made with it.
    void
    initialize_velocity_vector(VelocityVector &v) const;

    /**
     * Body-force hook: a load vector of the velocity space (layout of
     * initialize_velocity_vector()), condensed with
     * velocity_zero_constraints() (assemble it with
     * velocity_zero_constraints().distribute_local_to_global(), then
     * compress). Used from the next step on, until replaced.
     */
    void
    set_body_force(const VelocityVector &load);

    /**
     * A load that depends linearly on the new velocity, f = f_body - L v:
     * the semi-implicit coupling's L = Δt Sᵀ K S, the membrane forces'
     * change over the step (SemiImplicitLoad). The function adds L v to its
     * second argument (the layout of the body force, condensed with
     * velocity_zero_constraints()) for the velocity v of its first
     * (ghosted, constraints applied).
     */
    using VelocityLoad =
      std::function<void(const VelocityVector &, VelocityVector &)>;

    /**
     * Use @p load in the residual and the operator of every solve from the
     * next step on. L is never assembled: FGMRES applies J + L with the
     * preconditioner of J.
     */
    void
    set_velocity_load(const VelocityLoad &load);

    /// Advance the solution by one time step Δt. Throws SolverFailure.
    StepReport
    advance();

    FlowMeasures
    measure() const;

    /**
     * VTU (one piece per rank) and PVTU of v and p, and of the lab-frame
     * velocity v + V e_x (V the frame velocity), each piece carrying
     * @p field_data; returns the PVTU name.
     */
    std::string
    write_vtu(const std::string &directory,
              const unsigned int counter,
              const FieldData   &field_data = {}) const;

    /// (v, p), ghosted, with the constraints applied.
    const FluidVector &
    solution() const;
    const DoFHandler<3> &
    velocity_dof_handler() const;
    const DoFHandler<3> &
    pressure_dof_handler() const;
    /// Velocity and pressure DoFs together.
    types::global_dof_index
    n_dofs() const;
    const MappingQ<3> &
    get_mapping() const;
    /// The mapping of the multigrid's coarser levels.
    const MappingQ<3> &
    get_level_mapping() const;
    /// The velocity block's multigrid, whose levels a term can be added to
    /// (VelocityMultigrid::set_added_terms()).
    VelocityMultigrid &
    velocity_levels();
    /// Hanging nodes, periodicity and zero velocity on the Dirichlet
    /// boundaries: the constraints of load vectors and updates.
    const AffineConstraints<double> &
    velocity_zero_constraints() const;
    /// The DoFs of each multigrid level of the velocity, coarsest first.
    std::vector<types::global_dof_index>
    multigrid_dofs() const;

  private:
    void
    setup_dofs();
    void
    setup_solver(
      const std::vector<std::shared_ptr<const Triangulation<3>>> &levels);
    /**
     * Hanging nodes, periodicity, and on the Dirichlet boundaries the
     * drive's velocity in the frame U_frame scaled by @p scale, of the
     * velocity on @p dof_handler (a level's or the fine one) with
     * @p dof_mapping.
     */
    void
    make_velocity_constraints(const Mapping<3>          &dof_mapping,
                              const DoFHandler<3>       &dof_handler,
                              AffineConstraints<double> &constraints,
                              const double               scale) const;
    /// Hanging nodes and periodicity of the pressure.
    void
    make_pressure_constraints();
    /// Hanging nodes, periodicity and this step's boundary values on
    /// @p state (owned), then its ghosts.
    void
    apply_step_constraints(FluidVector &state);
    /**
     * Choose the first guess of a step (current) and assemble its residual;
     * returns its norm. Keeps vⁿ as earlier.
     */
    double
    start_step(const bool with_convection);
    double
    assemble_residual(const bool with_convection);
    /// The velocity's and the pressure's DoFs on a cell together.
    unsigned int
    n_dofs_per_cell() const;
    /// Set the owned entries of @p v from @p records, which hold the values
    /// of a field as cell_values() gives them from their @p offset on; then
    /// its ghosts.
    void
    set_cell_values(const CellRecords &records,
                    const unsigned int offset,
                    FluidVector       &v) const;
    /// Add the velocity load's L v to @p result for @p v (owned, any
    /// values at constrained DoFs: zero constraints are applied first).
    void
    add_field_load(const VelocityVector &v, VelocityVector &result) const;
    /// Solve (J + L) δ = -R and update; returns FGMRES's iterations and
    /// final residual.
    std::pair<unsigned int, double>
    solve_linear_system();
    /// measure()'s ‖∇·v‖ and largest |v| into @p measures.
    void
    measure_divergence_and_speed(FlowMeasures &measures) const;
    /// measure()'s flow rates through the outlet and pressure drop from
    /// the inlet to the outlet into @p measures.
    void
    measure_flow_through_ends(FlowMeasures &measures) const;

    const FluidParameters parameters;
    const FlowDrive       drive;
    double                time_step;
    const MPI_Comm        communicator;
    TimerOutput          &timer;

    const Triangulation<3> &triangulation;
    /// The quadratic mapping of the fine mesh, its support points computed
    /// once (every FEValues, point location and output reuses them);
    /// the multigrid's coarser meshes use level_mapping.
    MappingQCache<3>  mapping;
    const MappingQ<3> level_mapping;
    const FESystem<3> velocity_fe;
    const FE_Q<3>     pressure_fe;
    DoFHandler<3>     velocity_dofs;
    DoFHandler<3>     pressure_dofs;

    AffineConstraints<double> velocity_constraints; ///< homogeneous
    AffineConstraints<double> pressure_constraints;
    /// Hanging nodes and this frame velocity's boundary values; rebuilt
    /// only when the frame velocity changes.
    AffineConstraints<double> boundary_constraints;
    double                    frame_velocity = 0.;
    double                    constrained_frame_velocity =
      std::numeric_limits<double>::quiet_NaN();
    double residual_scale = 0.; ///< largest residual norm so far

    /// The levels below the fine mesh, coarsest first.
    std::vector<std::shared_ptr<const Triangulation<3>>> coarser_meshes;
    std::unique_ptr<StokesOperator>                      stokes;
    std::unique_ptr<VelocityMultigrid>                   velocity_multigrid;
    std::unique_ptr<StokesPreconditioner>                preconditioner;

    FluidVector current; ///< (v, p), ghosted
    /// vⁿ, ghosted: the velocity of the last step.
    VelocityVector previous_velocity;
    /// (vⁿ⁻¹, pⁿ⁻¹) in the current frame (size 0 until the first step),
    /// for the extrapolated first guess 2 vⁿ - vⁿ⁻¹ (start_step()).
    FluidVector earlier;
    /// That guess and its residual, the alternative to vⁿ's.
    FluidVector    extrapolated, extrapolated_residual;
    FluidVector    residual;
    FluidVector    update;
    VelocityVector body_force;
    VelocityLoad   velocity_load;
    /// Scratch of add_field_load(): a copy of v with its constraints.
    mutable VelocityVector load_field;
    VelocityVector         drive_load; ///< of the drive's pressure gradient
    VelocityVector         unit_axial_velocity; ///< v = e_x
  };

  /// "velocity multigrid: N levels of a, b, ... DoFs", coarsest first, for
  /// the log.
  std::string
  multigrid_levels_text(const FluidProblem &fluid);
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_ifem_ifem_simulation_h
#define rbc_ifem_ifem_ifem_simulation_h

#include <rbc_ifem/base/run_options.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/contact_gaps.h>
#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/coupling/multilevel_membrane_term.h>
#include <rbc_ifem/coupling/semi_implicit_load.h>
#include <rbc_ifem/coupling/time_step_limit.h>
#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/ifem/checkpoint.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/run_observer.h>
#include <rbc_ifem/ifem/run_record.h>
#include <rbc_ifem/ifem/run_report.h>
#include <rbc_ifem/ifem/size_estimate.h>
#include <rbc_ifem/ifem/step_schedule.h>
#include <rbc_ifem/ifem/volume_watch.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/fully_distributed_tria.h>

#include <memory>
#include <string>
#include <vector>

namespace rbc_ifem
{
  /**
   * Red cells carried by the plasma: the time loop of the immersed finite
   * element method of the paper's Sec. 2.2 (doc/design.md, "Immersed
   * coupling"), in the FlowDomain it is given. Each time step Δt:
   *
   *  1. the membrane positions xⁿ and the fluid velocity vⁿ are given;
   *  2. the forces Fⁿ = -∂E/∂x on the membrane points, the sum of the cell
   *     forces (CellPopulation, CellForce);
   *  3. spread to the fluid, f_J = Σ_I F_I φ_J(x_I) (ImmersedCoupling);
   *  4. solve the fluid for vⁿ⁺¹, pⁿ⁺¹ (FluidProblem, the constant Stokes
   *     operator and its preconditioner built once);
   *  5. interpolate v_I = Σ_J vⁿ⁺¹_J φ_J(x_I);
   *  6. move xⁿ⁺¹ = xⁿ + Δt v_I, and place the points on the mesh anew.
   *
   * With Immersed cells/Follow cells the frame follows the cells: after
   * each step its velocity becomes the cells' mean velocity, so that a cell
   * stays in the middle of a short segment; the fluid mesh, refined around
   * the cells' starting place, then stays fine where they are.
   *
   * After a step the run does what its StepSchedule says is due: every
   * Diffusion interval steps the CO uptake of the current membranes
   * (UptakeSolver: dm.csv, the P field and the flux map); every Time/Output
   * interval steps flow.csv, cells.csv (shape measures), the fluid and
   * membrane VTUs and the tables of its observers (RunObserver); every
   * Checkpoint interval steps a checkpoint (Checkpoint), from which Resume
   * continues. RunReport prints what it tells at the start and the end.
   *
   * A run that diverges (non-finite forces or fields, a point moving more
   * than Maximum step displacement of the mesh size in one step, a cell
   * leaving the fluid domain, the membranes of two cells crossing, a cell
   * reaching the capillary wall) stops with SolverFailure, after writing its
   * tables and the last good membranes.
   */
  class IFEMSimulation
  {
  public:
    /**
     * The run of @p parameters, whose parameters.prm is
     * @p parameter_file_text (a checkpoint carries it, and a resume refuses
     * a checkpoint of other parameters); times its sections in @p timer.
     * First, before it builds anything, it prints its SizeEstimate and
     * refuses a run larger than the machine's memory, unless @p options say
     * --force.
     */
    IFEMSimulation(const Parameters  &parameters,
                   const std::string &parameter_file_text,
                   const FlowDomain  &domain,
                   const MPI_Comm     communicator,
                   TimerOutput       &timer,
                   const RunOptions  &options = {});

    /// Add @p observer (which must outlive the run) to those run() calls.
    void
    add_observer(RunObserver &observer);

    /**
     * The fluid mesh, refined around the cells, the fluid, the coupling,
     * the start-up report and, with Resume, the checkpoint: everything that
     * can reject the input (InputError). Writes nothing.
     */
    void
    setup();

    /// The time loop, writing into Output directory, which must exist.
    void
    run();

  private:
    /**
     * The cell forces of the run besides the membranes' elasticity: the
     * tether, the pushing forces and the contact forces of Cell
     * interactions; throws InputError for pushing forces that do not match
     * the cells, or a squeeze without the wall.
     */
    void
    add_cell_forces();
    /// Throw InputError now, before the run writes anything, if the first
    /// DM solve would (a diffusion mesh too coarse for the membranes).
    void
    check_uptake_input() const;
    /**
     * The explicit coupling's time step estimate at the start: the
     * membranes' (CouplingTimeStepLimit), the repulsion's at the gaps the
     * cells start at, and the advective limit, in which a point at the
     * run's speed moves half of Immersed cells/Maximum step displacement.
     * Throws InputError if two cells start so close that the repulsion
     * would need a hundredth of the membranes' step.
     */
    CouplingTimeStepLimit
    time_step_limit() const;
    /**
     * Immersed cells/Coupling = semi-implicit: the fluid's velocity load
     * L = Δt Sᵀ K S (SemiImplicitLoad).
     */
    void
    setup_semi_implicit_load();
    /// The tables, fields and DM of t = 0.
    void
    record_start();
    /// RunReport::load_balance() of this rank's points and fluid cells.
    void
    report_load_balance() const;
    /**
     * What step record.step does after @p stepped (the fluid's report):
     * @p due's actions, flow.csv and the progress line, with the time left
     * from @p clock, started at step @p first_step.
     */
    void
    do_what_is_due(const StepActions &due,
                   const StepReport  &stepped,
                   const Timer       &clock,
                   const unsigned int first_step);
    /// Steps 2-6 and the frame update; returns the fluid's report.
    StepReport
    advance();
    /// Stop the run (restoring @p last_good) if a cell's volume has changed
    /// too much or oscillates with a growing amplitude (VolumeWatch).
    void
    watch_volumes(const std::vector<Vector<double>> &last_good);
    /// Stop the run (restoring @p last_good) if a point moves farther in
    /// one step with @p velocities than Maximum step displacement allows.
    void
    check_displacement(const std::vector<Tensor<1, 3>>   &velocities,
                       const std::vector<Vector<double>> &last_good);
    /// Solve the CO diffusion on the current membranes, add a dm.csv row.
    double
    solve_uptake(const unsigned int counter);
    void
    record_flow(const StepReport &report);
    /// Add the cells.csv rows of now, and tell the observers; returns the
    /// shapes.
    std::vector<CellShape>
    record_shapes();
    /// The gaps of every cell now; stops the run if membranes cross or a
    /// cell reaches the wall.
    std::vector<CellGaps>
    check_gaps(const std::vector<Vector<double>> &last_good);
    /// The smallest gap between the membranes of two cells now, and
    /// between a membrane and the wall [µm] (infinite where there is none).
    std::pair<double, double>
    smallest_gaps() const;
    /// The smallest gap between the membranes of two cells now [µm]
    /// (infinite for one cell).
    double
    smallest_cell_gap() const;
    /// The VTU field data of now: the time and the frame's velocity and
    /// offset.
    FieldData
    frame_data() const;
    void
    write_fields();
    void
    write_tables() const;
    void
    write_checkpoint() const;
    /// Resume from the checkpoint (Checkpoint::read() checks it).
    void
    read_checkpoint();
    /// The fluid's cell values of @p state (a rank's share of the blocks)
    /// for the cells this rank owns; an InputError naming Immersed
    /// cells/Resume if the checkpoint lacks some (collective).
    CellRecords
    fluid_cells_here(const CheckpointState &state) const;
    /// Write the tables and a checkpoint, then throw RunInterrupted.
    [[noreturn]] void
    save_and_stop(const int signal) const;
    /// Write the tables and the last good membranes, then throw; the
    /// message names the step in progress, or with @p after_step = true the
    /// step just done (a failure at its DM instant).
    [[noreturn]] void
    stop(const std::string                 &why,
         const std::vector<Vector<double>> &last_good,
         const bool                         after_step = false);

    const Parameters   parameters;
    const std::string  parameter_file_text;
    const MPI_Comm     communicator;
    const FlowDomain   domain;
    ConditionalOStream pcout;
    TimerOutput       &timer;
    /// Made, printed and checked before anything else is built.
    const SizeEstimate size_estimate;
    /// The fluid mesh: every rank builds and holds its part.
    parallel::fullydistributed::Triangulation<3> triangulation;
    FluidProblem                                 fluid;
    CellPopulation                               cells;
    /// The CO uptake solve of the cells' current shapes.
    const UptakeSolver                uptake;
    std::unique_ptr<ImmersedCoupling> coupling;
    /// The semi-implicit coupling's load; null for the explicit coupling.
    std::unique_ptr<SemiImplicitLoad> semi_implicit;
    /// L on the velocity multigrid's coarser levels too.
    std::unique_ptr<MultilevelMembraneTerm> multilevel_term;
    std::vector<RunObserver *>              observers;
    RunRecord                               record;
    const RunReport                         run_report;
    Checkpoint                              checkpoint;
    const StepSchedule                      schedule;
    VolumeWatch                             volume_watch;
    /// Whether anything can touch: several cells, or a wall.
    bool   contacts  = false;
    double mesh_size = 0.; ///< fluid h at the membranes [µm]
    double time_step = 0.; ///< Δt [s]: Time/Time step, or auto's choice
    VelocityVector load;   ///< the spread forces
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_ifem_simulation_h
#define rbc_ifem_ifem_simulation_h

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  /**
   * The time step limit of the explicit coupling [s]: a membrane wave of
   * wavenumber q relaxes in a Stokes fluid at the rate ω = E(q)/(4μq), E(q)
   * its stiffness per area, (K+G)q² in-plane and κq⁴ in bending; explicit
   * Euler needs ω Δt < 2. The shortest wave both the membrane points
   * (spacing s) and the Q2 fluid velocity (node spacing h/2) resolve has
   * q = π / max(s, h/2). Runs stay stable below about 0.7 of it (doc/ifem.md).
   */
  struct CouplingTimeStepLimit
  {
    double in_plane = 0.;
    double bending  = 0.;
    double limit    = 0.; ///< the smaller of the two

    CouplingTimeStepLimit(const double              viscosity,
                          const MembraneParameters &membrane,
                          const double              point_spacing,
                          const double              mesh_size);
  };

  /**
   * What a flowing run has produced so far and where it stands: the rows of
   * its tables, the records of its .pvd files, the step, the time and how
   * far the frame has moved. The tables are rewritten whole from it, so a
   * run that stops leaves complete files, and a checkpoint carries it.
   */
  struct RunRecord
  {
    unsigned int step   = 0;
    double       time   = 0.; ///< [s]
    double frame_offset = 0.; ///< distance the frame has moved along x [µm]
    std::vector<std::string>                    flow_rows, cell_rows, dm_rows;
    std::vector<std::pair<double, std::string>> fluid_files;
    std::vector<std::vector<std::pair<double, std::string>>>
                                                cell_files; ///< per cell
    std::vector<std::pair<double, std::string>> diffusion_files, flux_files;
    /// The shear box's capsule: time, Taylor deformation, inclination [rad].
    std::vector<std::array<double, 3>> shear_history;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &step &time &frame_offset &flow_rows &cell_rows &dm_rows
        &fluid_files &cell_files &diffusion_files &flux_files &shear_history;
    }
  };

  /**
   * Experiment "flow" with Immersed cells/Enabled, and each run of
   * Experiment "shear" (the FlowDomain says which): red cells carried by the
   * plasma, the immersed finite element method of the paper's Sec. 2.2
   * (design.md, "Immersed coupling"). Each time step Δt:
   *
   *  1. the membrane positions xⁿ and the fluid velocity vⁿ are given;
   *  2. the membrane forces Fⁿ = -∂E/∂x (CellPopulation, Membrane);
   *  3. spread to the fluid, f_J = Σ_I F_I φ_J(x_I) (ImmersedCoupling);
   *  4. solve the fluid for vⁿ⁺¹, pⁿ⁺¹ (FluidProblem, the constant Stokes
   *     operator and its preconditioner built once);
   *  5. interpolate v_I = Σ_J vⁿ⁺¹_J φ_J(x_I);
   *  6. move xⁿ⁺¹ = xⁿ + Δt v_I, and place the points on the mesh anew.
   *
   * The frame follows the cells (Immersed cells/Follow cells): after each
   * step its velocity becomes the cells' mean velocity, so that a cell stays
   * in the middle of a short segment; the fluid mesh, refined around the
   * cells' starting place, then stays fine where they are.
   *
   * Every Diffusion interval steps the CO diffusion is solved on the
   * current membranes (dm.csv, the P field and the flux map). The run writes
   * flow.csv every step, cells.csv (shape measures) and the fluid and
   * membrane VTUs every Time/Output interval steps, and a checkpoint every
   * Checkpoint interval steps, from which Resume continues.
   *
   * In the shear box the frame stays put and shear.csv records the
   * capsule's Taylor deformation and inclination (CellShape).
   *
   * A run that diverges (non-finite forces or fields, a point moving more
   * than Maximum step displacement of the mesh size in one step, a cell
   * leaving the fluid domain) stops with SolverFailure, after writing its
   * tables and the last good membranes.
   */
  class IFEMSimulation
  {
  public:
    IFEMSimulation(const Parameters &parameters,
                   const MPI_Comm    communicator,
                   const FlowDomain &domain);

    void
    run(const ParameterHandler &prm);

    /// What the run produced: its tables' rows and the shear history.
    const RunRecord &
    run_record() const;

  private:
    /// The fluid mesh, refined around the cells, the fluid, the coupling.
    void
    setup();
    /// The dimensionless numbers and stability estimates of the run.
    void
    report_startup() const;
    /// Steps 2-6 and the frame update; returns the fluid's report.
    StepReport
    advance();
    /// Solve the CO diffusion on the current membranes, add a dm.csv row.
    double
    solve_uptake(const unsigned int counter);
    void
    record_flow(const StepReport &report);
    /// Add the cells.csv rows of now; returns the shapes.
    std::vector<CellShape>
    record_shapes();
    void
    write_fields();
    void
    write_tables() const;
    void
    write_checkpoint() const;
    void
    read_checkpoint();
    /// Write the tables and the last good membranes, then throw.
    [[noreturn]] void
    stop(const std::string &why, const std::vector<Vector<double>> &last_good);

    const Parameters                   parameters;
    const MPI_Comm                     communicator;
    const FlowDomain                   domain;
    ConditionalOStream                 pcout;
    mutable TimerOutput                timer;
    parallel::shared::Triangulation<3> triangulation;
    FluidProblem                       fluid;
    CellPopulation                     cells;
    std::unique_ptr<ImmersedCoupling>  coupling;
    RunRecord                          record;
    double mesh_size = 0.;                   ///< fluid h at the membranes [µm]
    TrilinosWrappers::MPI::BlockVector load; ///< the spread forces, owned
  };
} // namespace rbc_ifem

#endif

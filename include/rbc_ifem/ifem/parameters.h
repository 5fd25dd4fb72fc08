#ifndef rbc_ifem_ifem_parameters_h
#define rbc_ifem_ifem_parameters_h

#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/coupling/time_step_limit.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// How the membrane forces enter the fluid step (Immersed cells/Coupling).
  enum class CouplingScheme
  {
    /// the forces at the start of the step (the paper's): Δt is bounded by
    /// the membrane stiffness
    explicit_forces,
    /// the forces at its end, linearised with the tangent stiffness K:
    /// the fluid operator gains Δt Sᵀ K S
    semi_implicit
  };

  const SelectionNames<CouplingScheme> &
  coupling_scheme_names();

  /// How a flowing run writes its membranes (Immersed cells/Membrane files).
  enum class MembraneFiles
  {
    /// cell_C_SSSS.vtu and cell_C.pvd for every cell C
    per_cell,
    /// membranes_SSSS.pvtu, one piece per rank with the cells it owns, and
    /// membranes.pvd
    grouped
  };

  /// The names of MembraneFiles in the parameter file.
  const SelectionNames<MembraneFiles> &
  membrane_files_names();

  /**
   * Time stepping of the flowing runs (subsection "Time"). The initializers
   * are the defaults (see GeometryParameters).
   */
  struct TimeParameters
  {
    /// Time/Time step as written: a number [s] or auto.
    std::string time_step_text = "auto";
    /// Δt [s] from time_step_text; 0 for auto (automatic_time_step()).
    double       time_step       = 0.;
    unsigned int n_steps         = 10;
    unsigned int output_interval = 1; ///< VTU every this many steps

    /// Whether the run chooses Δt: Time step = auto.
    bool
    automatic_time_step() const;
    /// Δt [s] of the plasma alone (no immersed cells): 1e-3 s for auto.
    double
    plasma_time_step() const;
    /// Δt [s] of a run with immersed cells whose explicit-coupling
    /// estimate is @p stable: for auto half its limit with the explicit
    /// coupling, semi_implicit_step_factor() times it with the
    /// semi-implicit, and in either case at most its advective limit.
    double
    coupled_time_step(const CouplingTimeStepLimit &stable,
                      const CouplingScheme         scheme) const;
    /// Time step = auto's Δt over the explicit estimate, semi-implicit.
    static constexpr double semi_implicit_step_factor = 10.;

    void
    add_parameters(ParameterHandler &prm);
  };

  /**
   * Experiment "flow" with red cells in the plasma, the immersed method
   * (subsection "Immersed cells"): what the time loop of IFEMSimulation
   * does besides the steps of subsection Time.
   */
  struct ImmersedParameters
  {
    bool enabled      = false; ///< carry the cells of subsection Layout
    bool follow_cells = true;  ///< frame velocity = the cells' mean velocity
    CouplingScheme coupling         = CouplingScheme::semi_implicit;
    unsigned int diffusion_interval = 0; ///< DM every this many steps; 0: never
    unsigned int checkpoint_interval = 0; ///< 0: never
    bool         resume = false; ///< from Output directory/checkpoint.bin
    double max_step_displacement = 0.25; ///< of the fluid mesh size h, per step
    double max_volume_change     = 0.05; ///< of a cell's reference volume
    unsigned int progress_interval =
      10; ///< a progress line every this many steps
    MembraneFiles membrane_files = MembraneFiles::per_cell;
    double tether_stiffness = 0.; ///< springs to the start [pN/µm]; 0: free
    /// Let a cell wider than the lumen start squeezed into it.
    bool squeeze_into_lumen = false;
    /// A constant force on each cell, "Fx, Fy, Fz; ..." [pN]; empty: none.
    std::string pushing_forces;

    /// The Pushing forces, one per cell listed.
    std::vector<Tensor<1, 3>>
    pushing_force_vectors() const;

    void
    add_parameters(ParameterHandler &prm);
    /// The entries of the coupling: Enabled, Follow cells, Coupling.
    void
    add_coupling_parameters(ParameterHandler &prm);
    /// The entries of what a run does when and writes: the intervals,
    /// Resume and Membrane files.
    void
    add_schedule_parameters(ParameterHandler &prm);
    /// The entries of the cells' guard and forces: Maximum step
    /// displacement, Tether stiffness, Squeeze into lumen, Pushing forces.
    void
    add_force_parameters(ParameterHandler &prm);
    /// Throws InputError for held cells in a moving frame.
    void
    validate() const;
  };
} // namespace rbc_ifem

#endif

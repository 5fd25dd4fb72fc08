#ifndef rbc_ifem_ifem_parameters_h
#define rbc_ifem_ifem_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

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
    /// estimate is @p limit: half of it for auto.
    double
    coupled_time_step(const double limit) const;

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
    unsigned int diffusion_interval = 0; ///< DM every this many steps; 0: never
    unsigned int checkpoint_interval = 0; ///< 0: never
    bool         resume = false; ///< from Output directory/checkpoint.bin
    double max_step_displacement = 0.25; ///< of the fluid mesh size h, per step
    unsigned int progress_interval =
      10;                         ///< a progress line every this many steps
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
    /// Throws InputError for held cells in a moving frame, or a zero
    /// Maximum step displacement.
    void
    validate() const;
  };
} // namespace rbc_ifem

#endif

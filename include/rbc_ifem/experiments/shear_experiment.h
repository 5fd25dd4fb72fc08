#ifndef rbc_ifem_shear_experiment_h
#define rbc_ifem_shear_experiment_h

#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <array>
#include <string>
#include <vector>

namespace rbc_ifem
{
  /// The steady state of one capsule run, a row of shear_summary.csv.
  struct ShearSummary
  {
    double capillary_number   = 0.;
    double steady_deformation = 0.; ///< mean D over the steadiest window
    double steady_inclination = 0.; ///< mean θ/π over the steadiest window
    double steady_from        = 0.; ///< γ̇ t where that window starts
    double steady_to          = 0.; ///< and where it ends
    double time_step          = 0.; ///< [s]
    unsigned int n_steps      = 0;
    double       wall_seconds = 0.;
  };

  /**
   * Experiment "shear": the classic validation of immersed methods, an
   * initially spherical capsule (Cells/Shape = sphere, radius a) at the
   * centre of a box in simple shear v = (γ̇ y, 0, 0) (FlowDomain::shear_box),
   * viscosity ratio 1. For each capillary number Ca = μ a γ̇ / G of
   * subsection Shear, the membrane moduli are scaled to give G, the time
   * step is a fraction of the explicit-coupling limit (which scales with
   * Ca), and an IFEMSimulation runs to the total strain γ̇ t in
   * Output directory/ca_<Ca>/, writing shear.csv (time, Taylor deformation
   * D = (L - B)/(L + B), inclination θ/π). shear_summary.csv gets the means
   * of D and θ/π over the steadiest window of Averaging strain of every run
   * (steady_state()).
   */
  class ShearExperiment
  {
  public:
    ShearExperiment(const Parameters &parameters, const MPI_Comm communicator);

    void
    run(const ParameterHandler &prm);

  private:
    /// The parameters of the run at @p capillary_number.
    Parameters
    parameters_for(const double capillary_number) const;

    /**
     * The steady state in a run's @p history (time, D, θ): of the windows
     * of Averaging strain between the samples, the one over which D changes
     * least, and the means of D and θ/π over it.
     */
    ShearSummary
    steady_state(const std::vector<std::array<double, 3>> &history) const;

    /// Run one capillary number and find its steady state.
    ShearSummary
    run_one(const double capillary_number, const ParameterHandler &prm) const;

    const Parameters   parameters;
    const MPI_Comm     communicator;
    ConditionalOStream pcout;
    double point_spacing = 0.; ///< of the capsule's membrane points [µm]
    double mesh_size     = 0.; ///< fluid cell edge at the capsule [µm]
  };
} // namespace rbc_ifem

#endif

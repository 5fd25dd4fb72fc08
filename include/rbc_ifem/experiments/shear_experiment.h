#ifndef rbc_ifem_experiments_shear_experiment_h
#define rbc_ifem_experiments_shear_experiment_h

#include <rbc_ifem/experiments/experiment.h>

#include <deal.II/base/tensor.h>

#include <array>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  class RunParameters;

  /**
   * Experiment "shear" (subsection "Shear"): one spherical capsule in the
   * middle of a box in simple shear v = (γ̇ y, 0, 0), run once for every
   * capillary number Ca = μ a γ̇ / G (a = Cells/Diameter / 2).
   */
  struct ShearParameters : public ExperimentParameters
  {
    double              shear_rate = 100.; ///< γ̇ [1/s]
    std::vector<double> capillary_numbers{0.0125, 0.025, 0.05, 0.1, 0.2};
    Tensor<1, 3>        box{
      {24., 24., 24.}}; ///< length (x), height (y), width (z) [µm]
    double strain = 4.;        ///< run length γ̇ t
    double averaging_strain =
      0.5; ///< steady values: means over the steadiest window of this γ̇ t
    double output_strain      = 0.25; ///< VTU and shear.csv every γ̇ t
    double time_step_fraction = 0.5;  ///< of the explicit-coupling limit

    void
    add_parameters(ParameterHandler &prm) override;
    /// Throws InputError unless the capsule fits and the strains make sense.
    void
    validate(const Parameters &parameters) const override;
  };

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
   * `Output directory/ca_<Ca>/`. Each run's parameters are derived from this
   * one's in a ParameterHandler (RunParameters::derive()), so its
   * parameters.prm is exactly what it runs; it writes shear.csv (time,
   * Taylor deformation D = (L - B)/(L + B), inclination θ/π) besides the
   * tables of every flowing run. shear_summary.csv gets the means of D and
   * θ/π over the steadiest window of Averaging strain of every run
   * (steady_state()).
   */
  class ShearExperiment : public Experiment
  {
  public:
    ShearExperiment(const ExperimentContext &context,
                    const ShearParameters   &shear);

    ~ShearExperiment() override;

  private:
    /// Every run's parameters, derived and checked.
    void
    setup() override;
    /// The runs, and shear_summary.csv after each.
    void
    execute() override;

    /// The parameters of the run at @p capillary_number, from these.
    std::unique_ptr<RunParameters>
    derive_run(const double capillary_number) const;

    /**
     * The steady state in a run's @p history (time, D, θ): of the windows
     * of Averaging strain between the samples, the one over which D changes
     * least, and the means of D and θ/π over it.
     */
    ShearSummary
    steady_state(const std::vector<std::array<double, 3>> &history) const;

    /// Run one capillary number and find its steady state.
    ShearSummary
    run_one(const double capillary_number, const RunParameters &run);

    const ShearParameters shear;
    double point_spacing = 0.; ///< of the capsule's membrane points [µm]
    double mesh_size     = 0.; ///< fluid cell edge at the capsule [µm]
    /// The parameters of each run, in the order of Shear/Capillary numbers.
    std::vector<std::unique_ptr<RunParameters>> runs;
  };
} // namespace rbc_ifem

#endif

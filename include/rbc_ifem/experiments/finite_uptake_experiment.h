#ifndef rbc_ifem_experiments_finite_uptake_experiment_h
#define rbc_ifem_experiments_finite_uptake_experiment_h

#include <rbc_ifem/experiments/uptake_experiment.h>

#include <memory>
#include <string>
#include <vector>

namespace rbc_ifem
{
  /// The θ_CO sweep of experiment "finite uptake" (subsection "Finite
  /// uptake").
  struct FiniteUptakeParameters : public ExperimentParameters
  {
    /// The formulas θ(PO₂) to sweep.
    std::vector<ThetaModel> theta_models{ThetaModel::roughton_forster_1957,
                                         ThetaModel::forster_1987,
                                         ThetaModel::guenard_2016};
    /// PO₂ [Torr], each turned into θ by each of the theta_models.
    std::vector<double> oxygen_pressures{100., 600.};
    /// θ_CO given directly [mL CO min⁻¹ Torr⁻¹ per mL of blood].
    std::vector<double> thetas{0.3, 1.22, 10.};

    void
    add_parameters(ParameterHandler &prm) override;
    /// Cut cells, formulas for the oxygen pressures, θ > 0.
    void
    validate(const Parameters &parameters) const override;
  };

  /**
   * Experiment "finite uptake" (doc/physiology.md): for every layout of
   * subsection Layout study (one cell once, whatever the kinds), DM (the
   * membrane sink) and DL, the uptake with CO bound inside the cells at the
   * rate θ_CO, for each θ of the sweep, on one uptake mesh per layout; beside
   * it Roughton and Forster's lumped estimate 1/DL = 1/DM + 1/(θ V_c), V_c the
   * blood volume of the cells (their volume / Diffusion/Hematocrit). Writes
   * uptake.csv: layout, n_cells, seed, cells_volume [µm³], theta_source,
   * oxygen_pressure [Torr], theta [mL CO min⁻¹ Torr⁻¹ per mL of blood],
   * dm_total, dl_total, roughton_forster_dl [µm³ s⁻¹ Torr⁻¹],
   * roughton_forster_error (the lumped estimate / DL − 1), dl_iterations.
   */
  class FiniteUptakeExperiment : public UptakeExperiment
  {
  public:
    FiniteUptakeExperiment(const ExperimentContext      &context,
                           const FiniteUptakeParameters &sweep);

  private:
    /// Every layout of the study, built and checked.
    void
    setup() override;
    void
    execute() override;

    /// One θ of the sweep: where it comes from and its value.
    struct Theta
    {
      std::string source;          ///< "given" or the Theta model's name
      std::string oxygen_pressure; ///< [Torr], empty for a given θ
      double      value; ///< [mL CO min⁻¹ Torr⁻¹ per mL of blood]
    };

    /// The θ of the sweep, in order: each formula's at each oxygen
    /// pressure, then the given ones.
    std::vector<Theta>
    thetas() const;

    const FiniteUptakeParameters                    sweep;
    std::vector<std::unique_ptr<const PlacedCells>> layouts;
  };
} // namespace rbc_ifem

#endif

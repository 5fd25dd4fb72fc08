#ifndef rbc_ifem_diffusion_oxygen_parameters_h
#define rbc_ifem_diffusion_oxygen_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The rate q(P, S) at which hemoglobin binds O2 [s⁻¹: saturation per
   * second] and its derivatives, at one point.
   */
  struct BindingRate
  {
    double q;
    double dq_dP; ///< [s⁻¹ Torr⁻¹]
    double dq_dS; ///< [s⁻¹]
  };

  /**
   * How hemoglobin binds O2: the rate q(P, S) of the saturation's change
   * at PO₂ P and saturation S. CutCellOxygen takes any; HillBinding is the
   * model's, a linear one serves the exact test.
   */
  class OxygenBinding
  {
  public:
    virtual ~OxygenBinding() = default;

    /// q and its derivatives at (P, S).
    virtual BindingRate
    rate(const double P, const double S) const = 0;

    /// The saturation in equilibrium with P: q(P, S) = 0.
    virtual double
    equilibrium_saturation(const double P) const = 0;
  };

  /**
   * Hill kinetics, q = k_d [(1 − S)(P/P50)^n − S]: in equilibrium
   * S/(1 − S) = (P/P50)^n. A P below zero (a solver's undershoot) binds
   * nothing: (P/P50)^n is taken at max(P, 0).
   */
  class HillBinding : public OxygenBinding
  {
  public:
    /// @p p50 [Torr], Hill coefficient @p n, dissociation rate @p k_d [s⁻¹].
    HillBinding(const double p50, const double n, const double k_d);

    BindingRate
    rate(const double P, const double S) const override;

    double
    equilibrium_saturation(const double P) const override;

  private:
    const double p50, n, k_d;
  };

  /**
   * O2 in the capillary and its cells (subsection "Oxygen"): the partial
   * pressure P in the plasma, the wall, the gas layer and the cytoplasm,
   * α ∂P/∂t = ∇·(αD ∇P) − C q inside the cells, and the hemoglobin
   * saturation S inside them, ∂S/∂t = D_Hb ∇²S + q (Hill binding, no flux
   * of S through the membranes). Amounts of O2 are gas volumes (STPD) per
   * volume, so α is in Torr⁻¹ and C in µm³ O2 per µm³ of cytoplasm. The
   * defaults are those ETHZ-CFD-MS/O2RBC's tutorials list after Eggleton
   * et al. (2000), converted with the STPD molar volume 22,400 mL/mol
   * (not the 25,440 mL/mol at 37 °C).
   */
  struct OxygenParameters
  {
    double alveolar_pressure      = 100.;    ///< P_A [Torr]
    double venous_pressure        = 40.;     ///< P_v [Torr]
    double p50                    = 26.8;    ///< [Torr]
    double hill_coefficient       = 2.7;     ///< n
    double dissociation_rate      = 44.;     ///< k_d [s⁻¹]
    double heme_capacity          = 0.455;   ///< C_Hb [µm³ O2 / µm³]
    double hemoglobin_diffusivity = 14.4;    ///< D_Hb [µm²/s]
    double plasma_solubility      = 2.82e-5; ///< α [Torr⁻¹]
    double plasma_diffusivity     = 2180.;   ///< D [µm²/s]
    double wall_solubility        = 3.89e-5;
    double wall_diffusivity       = 873.;
    double cytoplasm_solubility   = 3.38e-5;
    double cytoplasm_diffusivity  = 950.;
    double gas_solubility         = 1.159e-3;
    double gas_diffusivity        = 2.2e7;

    void
    add_parameters(ParameterHandler &prm);

    /// The Hill binding of these parameters.
    HillBinding
    binding() const;

    /// α of the material with this id (Material::plasma, ...) [Torr⁻¹].
    double
    solubility(const unsigned int material_id) const;

    /// αD of the material with this id [µm²/(s Torr)].
    double
    permeability(const unsigned int material_id) const;
  };
} // namespace rbc_ifem

#endif

#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/diffusion/oxygen_parameters.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  HillBinding::HillBinding(const double p50, const double n, const double k_d)
    : p50(p50)
    , n(n)
    , k_d(k_d)
  {}

  BindingRate
  HillBinding::rate(const double P, const double S) const
  {
    if (P <= 0.)
      return {-k_d * S, 0., -k_d};
    const double x = std::pow(P / p50, n);
    return {k_d * ((1. - S) * x - S),
            k_d * (1. - S) * n * x / P,
            -k_d * (x + 1.)};
  }

  double
  HillBinding::equilibrium_saturation(const double P) const
  {
    const double x = std::pow(std::max(P, 0.) / p50, n);
    return x / (1. + x);
  }

  HillBinding
  OxygenParameters::binding() const
  {
    return HillBinding(p50, hill_coefficient, dissociation_rate);
  }

  double
  OxygenParameters::solubility(const unsigned int material_id) const
  {
    switch (material_id)
      {
        case Material::plasma:
          return plasma_solubility;
        case Material::vessel_wall:
          return wall_solubility;
        case Material::gas:
          return gas_solubility;
        default:
          throw std::logic_error("no O2 data for material id " +
                                 std::to_string(material_id));
      }
  }

  double
  OxygenParameters::permeability(const unsigned int material_id) const
  {
    switch (material_id)
      {
        case Material::plasma:
          return plasma_solubility * plasma_diffusivity;
        case Material::vessel_wall:
          return wall_solubility * wall_diffusivity;
        case Material::gas:
          return gas_solubility * gas_diffusivity;
        default:
          throw std::logic_error("no O2 data for material id " +
                                 std::to_string(material_id));
      }
  }

  void
  OxygenParameters::add_parameters(ParameterHandler &prm)
  {
    const std::string source =
      "ETHZ-CFD-MS/O2RBC's tutorials after Eggleton et al. (2000), "
      "converted with the STPD molar volume 22,400 mL/mol";
    prm.enter_subsection("Oxygen");
    add_parameter(prm,
                  "Alveolar PO2",
                  alveolar_pressure,
                  "O2 partial pressure P_A on the outer surface of the gas "
                  "layer [Torr] (100 at rest at sea level, about 50 at "
                  "altitude).",
                  GreaterThan());
    add_parameter(prm,
                  "Venous PO2",
                  venous_pressure,
                  "O2 partial pressure P_v of the blood entering the "
                  "capillary [Torr] (40 at rest, about 25 in exercise): at "
                  "the start P = P_v everywhere but on the alveolar surface, "
                  "and S is in equilibrium with it. It may exceed Alveolar "
                  "PO2: the cells then unload O2.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "P50",
                  p50,
                  "PO2 at which hemoglobin is half saturated [Torr] (human "
                  "blood, pH 7.4, 37 °C).",
                  GreaterThan());
    add_parameter(prm,
                  "Hill coefficient",
                  hill_coefficient,
                  "n of the Hill binding, S/(1 − S) = (P/P50)^n in "
                  "equilibrium (dimensionless, > 0; human blood 2.7).",
                  GreaterThan());
    add_parameter(prm,
                  "Dissociation rate",
                  dissociation_rate,
                  "k_d of q = k_d [(1 − S)(P/P50)^n − S], the rate of the "
                  "saturation's change [s⁻¹] (" +
                    source + ").",
                  GreaterThan());
    add_parameter(prm,
                  "Heme capacity",
                  heme_capacity,
                  "C_Hb: the O2 the cytoplasm binds at S = 1 [µm³ O2 (STPD) "
                  "per µm³ of cytoplasm]: 20.3 mol heme per m³ times "
                  "22,400 mL/mol (" +
                    source + ").",
                  GreaterThan());
    add_parameter(prm,
                  "Hemoglobin diffusivity",
                  hemoglobin_diffusivity,
                  "D_Hb of the saturation inside the cells [µm²/s], > 0 "
                  "(the S rows need it: a cut cell's sliver of S is held "
                  "where its rows are round-off) (" +
                    source + ").",
                  GreaterThan());
    const auto add_material = [&](const std::string &name,
                                  double            &solubility,
                                  double            &diffusivity,
                                  const std::string &where,
                                  const std::string &from) {
      add_parameter(prm,
                    name + " solubility",
                    solubility,
                    "O2 solubility α in the " + where +
                      " [Torr⁻¹: volume of O2 (STPD) per volume per Torr] (" +
                      from + ").",
                    GreaterThan());
      add_parameter(prm,
                    name + " diffusivity",
                    diffusivity,
                    "O2 diffusion coefficient D in the " + where +
                      " [µm²/s] (" + from + ").",
                    GreaterThan());
    };
    add_material(
      "Plasma", plasma_solubility, plasma_diffusivity, "plasma", source);
    add_material(
      "Wall", wall_solubility, wall_diffusivity, "vessel wall", source);
    add_material("Cytoplasm",
                 cytoplasm_solubility,
                 cytoplasm_diffusivity,
                 "cytoplasm of the red cells",
                 source);
    add_material("Gas",
                 gas_solubility,
                 gas_diffusivity,
                 "alveolar gas layer",
                 "an ideal gas at 37 °C, (1/760)(273.15/310.15); D of O2 "
                 "in nitrogen at 37 °C, about 0.22 cm²/s: the layer's "
                 "resistance is negligible whatever the value");
    prm.leave_subsection();
  }
} // namespace rbc_ifem

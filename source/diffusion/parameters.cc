#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/diffusion/parameters.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace rbc_ifem
{
  namespace
  {
    const SelectionNames<DiffusionMethod> &
    method_names()
    {
      static const SelectionNames<DiffusionMethod> names{
        {DiffusionMethod::lagrange_multiplier, "Lagrange multiplier"},
        {DiffusionMethod::cut_cell, "cut cell"}};
      return names;
    }

    const SelectionNames<CellUptake> &
    uptake_names()
    {
      static const SelectionNames<CellUptake> names{
        {CellUptake::membrane_sink, "membrane sink"},
        {CellUptake::reaction, "reaction"}};
      return names;
    }
  } // namespace

  const SelectionNames<ThetaModel> &
  theta_model_names()
  {
    static const SelectionNames<ThetaModel> names{
      {ThetaModel::given, "given"},
      {ThetaModel::roughton_forster_1957, "Roughton-Forster 1957"},
      {ThetaModel::forster_1987, "Forster 1987"},
      {ThetaModel::guenard_2016, "Guenard 2016"}};
    return names;
  }

  void
  DiffusionParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Diffusion");
    add_material_parameters(prm);
    add_method_parameters(prm);
    add_solver_parameters(prm);
    add_reaction_parameters(prm);
    prm.leave_subsection();
  }

  void
  DiffusionParameters::add_material_parameters(ParameterHandler &prm)
  {
    add_parameter(prm,
                  "Alveolar pressure",
                  alveolar_pressure,
                  "CO partial pressure P_A on the outer surface of the gas "
                  "layer [Torr]. DM = CO flow / P_A does not depend on it.",
                  GreaterThan());
    const auto add_material = [&](const std::string &name,
                                  double            &diffusivity,
                                  double            &solubility,
                                  const std::string &where,
                                  const std::string &solubility_source) {
      add_parameter(prm,
                    name + " diffusivity",
                    diffusivity,
                    "CO diffusion coefficient D in the " + where +
                      " [µm²/s] (the paper's Table 2).",
                    GreaterThan());
      add_parameter(prm,
                    name + " solubility",
                    solubility,
                    "CO solubility α in the " + where +
                      " [Torr⁻¹: volume of CO (STPD) per volume per Torr] (" +
                      solubility_source + ").",
                    GreaterThan());
    };
    add_material("Plasma",
                 plasma_diffusivity,
                 plasma_solubility,
                 "plasma (the lumen)",
                 "the paper's Table 2");
    add_material("Wall",
                 wall_diffusivity,
                 wall_solubility,
                 "vessel wall tissue",
                 "the paper's Table 2");
    add_material("Gas",
                 gas_diffusivity,
                 gas_solubility,
                 "alveolar gas",
                 "an ideal gas at 37 °C: (1/760) (273.15/310.15) = "
                 "1.159e-3");
  }

  void
  DiffusionParameters::add_method_parameters(ParameterHandler &prm)
  {
    add_selection(
      prm,
      "Method",
      method,
      method_names(),
      "How P = 0 is imposed on the membranes, which cut through the "
      "diffusion mesh. cut cell (the default): the plasma is the part of the mesh outside a "
      "level set of the membranes (their signed distance), P = 0 is imposed "
      "by Nitsche's method on the cut cells, stabilised by a ghost penalty; "
      "DM converges at order >= 2 and the membranes may be as fine as "
      "wanted. Lagrange multiplier (the paper's kind of method, kept for "
      "comparison): a multiplier on each membrane, the flux is its value; "
      "DM converges at order ~1, the membranes must be about twice as "
      "coarse as the mesh around them. See doc/diffusion.md.");
    add_parameter(prm,
                  "Finite element degree",
                  degree,
                  "Degree k of the continuous FE_Q<3>(k) for P (the mapping "
                  "has the same degree).",
                  Patterns::Integer(1, 3));
    add_parameter(prm,
                  "Augmentation",
                  augmentation,
                  "Augmented-Lagrangian weight γ (dimensionless) of the "
                  "membrane constraint. It does not change the solution, "
                  "only the solver: larger γ makes the multiplier block "
                  "easier and the P block harder. See doc/diffusion.md.",
                  GreaterThan());
    add_parameter(prm,
                  "Nitsche penalty",
                  nitsche_penalty,
                  "cut cell only: the Nitsche penalty on the membranes is "
                  "this times k(k+1) αD/h (k the degree, h the cell size); "
                  "dimensionless. Too small (below about 1) loses "
                  "coercivity; larger values only cost accuracy slowly.",
                  GreaterThan());
    add_parameter(prm,
                  "Ghost penalty",
                  ghost_penalty,
                  "cut cell only: weight of the ghost penalty (the jumps of "
                  "the normal derivatives of order 1 to k across the faces "
                  "of cut cells, scaled by αD h^(2j-1)), dimensionless. It "
                  "keeps the system well conditioned however small the "
                  "plasma part of a cut cell is. The penalty is only weakly "
                  "consistent, and on coarse meshes it is most of the "
                  "error: seven cells at band refinements 1 take up 0.53% "
                  "more than the limit with 0.05, 0.14% more with 0.01. "
                  "Below about 0.005 CG needs more iterations "
                  "(doc/diffusion.md).",
                  GreaterThan());
  }

  void
  DiffusionParameters::add_solver_parameters(ParameterHandler &prm)
  {
    add_parameter(prm,
                  "Linear solver tolerance",
                  linear_tolerance,
                  "The linear solver (FGMRES for the multiplier, CG for cut "
                  "cells) stops when the residual has fallen by this "
                  "factor from its first value in the solve. (Fluid/Linear "
                  "solver tolerance is relative to the largest residual of "
                  "the whole run instead.)",
                  GreaterThan());
    add_parameter(prm,
                  "Max linear iterations",
                  max_linear_iterations,
                  "The linear solver gives up (and the run stops) after this "
                  "many iterations.",
                  Patterns::Integer(1));
  }

  void
  DiffusionParameters::add_reaction_parameters(ParameterHandler &prm)
  {
    add_selection(
      prm,
      "Uptake",
      uptake,
      uptake_names(),
      "What the red cells do with CO. membrane sink (the paper's model): "
      "P = 0 on every membrane, CO is bound the instant it enters; the "
      "result is DM. reaction: CO diffuses on into the cytoplasm "
      "(Cytoplasm diffusivity and solubility) and is bound there at the "
      "finite rate θ_CO (Theta model); each uptake solve then also solves "
      "this problem and dm.csv gains dl_total,dl_cell_i, the diffusing "
      "capacity DL it gives. Needs Method = cut cell (doc/physiology.md).");
    add_parameter(prm,
                  "Cytoplasm diffusivity",
                  cytoplasm_diffusivity,
                  "reaction only: CO diffusion coefficient D inside the red "
                  "cells [µm²/s]. An assumption, not a measured value: "
                  "small gases diffuse in the cells' concentrated "
                  "hemoglobin (33 g/dL) at roughly a third of their speed "
                  "in plasma; doc/physiology.md shows how DL depends on it.",
                  GreaterThan());
    add_parameter(prm,
                  "Cytoplasm solubility",
                  cytoplasm_solubility,
                  "reaction only: CO solubility α inside the red cells "
                  "[Torr⁻¹], the plasma's: the Bunsen coefficients of CO "
                  "at 37 °C in saline and in whole blood, 0.0180 and "
                  "0.0189, differ by 5% (doc/physiology.md).",
                  GreaterThan());
    add_selection(
      prm,
      "Theta model",
      theta_model,
      theta_model_names(),
      "reaction only: where θ_CO, the CO uptake of blood per Torr of CO "
      "pressure in its plasma [mL CO min⁻¹ Torr⁻¹ per mL of blood], comes "
      "from. given: Theta. The others are 1/θ = a + b PO₂ for blood of "
      "14.6 g/dL hemoglobin, as the ATS/ERS standard lists them (Zavorsky "
      "et al., Eur. Respir. J. 49 (2017) 1600962): Roughton-Forster 1957 "
      "1.0 + 0.0058 PO₂ (pH 8.0), Forster 1987 1.30 + 0.0041 PO₂ (pH 7.4), "
      "Guenard 2016 1.16 + 0.0062 PO₂ (the standard's recommendation). PO₂ "
      "is Oxygen pressure.");
    add_parameter(prm,
                  "Theta",
                  theta,
                  "reaction, Theta model = given: θ_CO [mL CO min⁻¹ "
                  "Torr⁻¹ per mL of blood]. The default, 1/0.82, is the "
                  "thin-film measurements' (Hughes & van der Lee, Eur. "
                  "Respir. J. 41 (2013) 453, Table 4).",
                  GreaterThan());
    add_parameter(prm,
                  "Oxygen pressure",
                  oxygen_pressure,
                  "reaction: the O₂ partial pressure PO₂ the Theta model "
                  "takes [Torr]; about 100 in alveolar capillaries at rest.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Hematocrit",
                  hematocrit,
                  "reaction: the volume fraction H of cells in the blood "
                  "θ_CO is given for (dimensionless, 0 < H <= 1); the "
                  "cytoplasm binds θ/H per mL of cells. The formulas' "
                  "14.6 g/dL of hemoglobin is H = 0.44 at the normal 33 "
                  "g/dL inside the cells.",
                  GreaterThan(0., 1.));
  }

  void
  DiffusionParameters::validate() const
  {
    if (uptake == CellUptake::reaction && method != DiffusionMethod::cut_cell)
      throw InputError("Diffusion/Uptake",
                       "reaction",
                       "the reaction inside the cells needs the cell "
                       "interiors in the mesh: set Diffusion/Method = cut "
                       "cell (it is '" +
                         name_of(method, method_names()) + "').");
  }

  double
  DiffusionParameters::theta_blood() const
  {
    switch (theta_model)
      {
        case ThetaModel::roughton_forster_1957:
          return 1. / (1.0 + 0.0058 * oxygen_pressure);
        case ThetaModel::forster_1987:
          return 1. / (1.30 + 0.0041 * oxygen_pressure);
        case ThetaModel::guenard_2016:
          return 1. / (1.16 + 0.0062 * oxygen_pressure);
        default:
          return theta;
      }
  }

  double
  DiffusionParameters::reaction_rate() const
  {
    return theta_blood() / hematocrit / 60.;
  }

  double
  DiffusionParameters::cytoplasm_permeability() const
  {
    return cytoplasm_solubility * cytoplasm_diffusivity;
  }

  double
  DiffusionParameters::permeability(const unsigned int material_id) const
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
          throw std::logic_error("no CO diffusion data for material id " +
                                 std::to_string(material_id));
      }
  }
} // namespace rbc_ifem

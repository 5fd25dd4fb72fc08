#ifndef rbc_ifem_diffusion_parameters_h
#define rbc_ifem_diffusion_parameters_h

#include <rbc_ifem/base/parameter_tools.h>

#include <deal.II/base/parameter_handler.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Steady CO diffusion (subsection "Diffusion"): ∇·(αD∇P) = 0 with αD
   * piecewise constant per material, P = P_A on the alveolar surface and
   * P = 0 on every membrane (imposed by a Lagrange multiplier, see
   * CODiffusion, or by Nitsche's method on cut cells, CutCellDiffusion).
   * Defaults from the paper's Table 2; the initializers are the defaults (see
   * GeometryParameters).
   */
  /// How P = 0 is imposed on the membranes (Diffusion/Method).
  enum class DiffusionMethod
  {
    lagrange_multiplier, ///< CODiffusion
    cut_cell             ///< CutCellDiffusion
  };

  /// What happens to CO at the membranes (Diffusion/Uptake).
  enum class CellUptake
  {
    membrane_sink, ///< P = 0 on the membranes: DM (the paper's model)
    reaction       ///< CO bound inside the cells at the rate θ: DL beside DM
  };

  /**
   * Where θ_CO comes from (Diffusion/Theta model): Diffusion/Theta, or
   * 1/θ = a + b PO₂ with a and b as the ATS/ERS standard (Zavorsky et al.,
   * Eur. Respir. J. 49 (2017) 1600962, its table of θ equations) lists them
   * for blood of 14.6 g/dL hemoglobin.
   */
  enum class ThetaModel
  {
    given,                 ///< Diffusion/Theta
    roughton_forster_1957, ///< 1/θ = 1.0 + 0.0058 PO₂ (pH 8.0)
    forster_1987,          ///< 1/θ = 1.30 + 0.0041 PO₂ (pH 7.4)
    guenard_2016           ///< 1/θ = 1.16 + 0.0062 PO₂ (the recommended one)
  };

  /// The names Diffusion/Theta model spells the ThetaModel values with.
  const SelectionNames<ThetaModel> &
  theta_model_names();

  struct DiffusionParameters
  {
    DiffusionMethod method                = DiffusionMethod::cut_cell;
    double          alveolar_pressure     = 1.;       ///< P_A [Torr]
    double          plasma_diffusivity    = 2.453e3;  ///< D [µm²/s]
    double          plasma_solubility     = 2.363e-5; ///< α [Torr⁻¹]
    double          wall_diffusivity      = 2.453e3;  ///< D [µm²/s]
    double          wall_solubility       = 2.363e-5; ///< α [Torr⁻¹]
    double          gas_diffusivity       = 2.413e7;  ///< D [µm²/s]
    double          gas_solubility        = 1.159e-3; ///< α [Torr⁻¹]
    unsigned int    degree                = 2;        ///< of FE_Q<3> for P
    double          augmentation          = 30.;      ///< γ, dimensionless
    double          nitsche_penalty       = 5.;   ///< × k(k+1), dimensionless
    double          ghost_penalty         = 0.01; ///< dimensionless
    double          linear_tolerance      = 1e-8; ///< relative, FGMRES
    unsigned int    max_linear_iterations = 1000;
    CellUptake      uptake                = CellUptake::membrane_sink;
    double          cytoplasm_diffusivity = 7.0e2;    ///< D [µm²/s]
    double          cytoplasm_solubility  = 2.363e-5; ///< α [Torr⁻¹]
    ThetaModel      theta_model           = ThetaModel::guenard_2016;
    /// θ_CO [mL CO min⁻¹ Torr⁻¹ per mL of blood] if theta_model is given.
    double theta           = 1.22;
    double oxygen_pressure = 100.; ///< PO₂ in the cells [Torr]
    /// Volume fraction of cells in the blood θ refers to.
    double hematocrit = 0.44;

    /// θ_CO of theta_model [mL CO min⁻¹ Torr⁻¹ per mL of blood].
    double
    theta_blood() const;

    /**
     * The rate k at which the cytoplasm binds CO, k P per unit volume of
     * cell [µm³ of CO per µm³ and s, k in s⁻¹ Torr⁻¹]: θ per mL of cells
     * (θ / hematocrit) per second.
     */
    double
    reaction_rate() const;

    /// α D of the cytoplasm [µm²/(s Torr)].
    double
    cytoplasm_permeability() const;

    /// αD of the material with this id (Material::plasma, ...) [µm²/(s Torr)].
    double
    permeability(const unsigned int material_id) const;

    void
    add_parameters(ParameterHandler &prm);
    /// The entries of the materials: P_A, and D and α of each layer.
    void
    add_material_parameters(ParameterHandler &prm);
    /// The entries of the discretisation: method, degree and penalties.
    void
    add_method_parameters(ParameterHandler &prm);
    /// The entries of the linear solver.
    void
    add_solver_parameters(ParameterHandler &prm);
    /// The entries of the reaction inside the cells (Uptake and after).
    void
    add_reaction_parameters(ParameterHandler &prm);
    /// Throws InputError unless the reaction has cut cells (the patterns
    /// hold every coefficient and tolerance > 0).
    void
    validate() const;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_diffusion_parameters_h
#define rbc_ifem_diffusion_parameters_h

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

  struct DiffusionParameters
  {
    DiffusionMethod method             = DiffusionMethod::lagrange_multiplier;
    double          alveolar_pressure  = 1.;       ///< P_A [Torr]
    double          plasma_diffusivity = 2.453e3;  ///< D [µm²/s]
    double          plasma_solubility  = 2.363e-5; ///< α [Torr⁻¹]
    double          wall_diffusivity   = 2.453e3;  ///< D [µm²/s]
    double          wall_solubility    = 2.363e-5; ///< α [Torr⁻¹]
    double          gas_diffusivity    = 2.413e7;  ///< D [µm²/s]
    double          gas_solubility     = 1.159e-3; ///< α [Torr⁻¹]
    unsigned int    degree             = 1;        ///< of FE_Q<3> for P
    double          augmentation       = 30.;      ///< γ, dimensionless
    double          nitsche_penalty    = 5.;       ///< × k(k+1), dimensionless
    double          ghost_penalty      = 0.01;     ///< dimensionless
    double          linear_tolerance   = 1e-8;     ///< relative, FGMRES
    unsigned int    max_linear_iterations = 1000;

    /// αD of the material with this id (Material::plasma, ...) [µm²/(s Torr)].
    double
    permeability(const unsigned int material_id) const;

    void
    add_parameters(ParameterHandler &prm);
    /// Throws InputError unless every coefficient and tolerance is > 0.
    void
    validate() const;
  };
} // namespace rbc_ifem

#endif

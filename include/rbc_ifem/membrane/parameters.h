#ifndef rbc_ifem_membrane_parameters_h
#define rbc_ifem_membrane_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The red cell membrane's mechanics (subsection "Membrane"): energies and
   * moduli in pN and µm. See Membrane and doc/membrane.md. The initializers
   * are the defaults (see GeometryParameters).
   */
  struct MembraneParameters
  {
    /// The name of an ElasticLaw (elastic_law_names()).
    std::string  law                   = "neo-Hookean";
    double       shear_modulus         = 5.5;  ///< G_s [pN/µm]
    double       area_dilation_modulus = 500.; ///< K [pN/µm]
    double       bending_modulus       = 0.2;  ///< κ [pN µm]
    double       spontaneous_curvature = 0.;   ///< c0 [1/µm]
    double       area_penalty          = 500.; ///< k_A [pN/µm]
    double       volume_penalty        = 500.; ///< k_V [pN/µm²]
    unsigned int degree                = 1;    ///< of FE_Q<2,3>

    void
    add_parameters(ParameterHandler &prm);
    /// Throws InputError unless G > 0 and the law can have G and K.
    void
    validate() const;
  };
} // namespace rbc_ifem

#endif

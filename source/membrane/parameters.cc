#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/membrane/elastic_law.h>
#include <rbc_ifem/membrane/parameters.h>

namespace rbc_ifem
{
  void
  MembraneParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Membrane");
    add_parameter(prm,
                  "Elastic law",
                  law,
                  "In-plane hyperelastic law, in the principal stretches "
                  "λ1, λ2 of the surface deformation. neo-Hookean (the "
                  "paper's): W = C1 (λ1² + λ2² + 1/(λ1λ2)² - 3) + C2/2 "
                  "(λ1λ2 - 1)², C1 = G/2, C2 = K - 3G. Skalak: W = G/4 "
                  "(I1² + 2 I1 - 2 I2 + C I2²), I1 = λ1² + λ2² - 2, I2 = "
                  "(λ1λ2)² - 1, C = (K/G - 1)/2.",
                  Patterns::Selection(join_names(elastic_law_names())));
    add_parameter(prm,
                  "Shear modulus",
                  shear_modulus,
                  "In-plane shear modulus G [pN/µm]; 5.5 pN/µm is the "
                  "value optical-tweezers experiments give (Mills et al. "
                  "2004: 5.3-7.3).",
                  GreaterThan());
    add_parameter(prm,
                  "Area dilation modulus",
                  area_dilation_modulus,
                  "Local area dilation modulus K [pN/µm] (small-strain "
                  "tension per relative area change). The real membrane's "
                  "is ~3e5 pN/µm; 500 keeps local area changes below ~2% "
                  "at 200 pN while the solver stays fast. Must be at "
                  "least 3G for the neo-Hookean law (K = 3G is its classical "
                  "form, C2 = 0).",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Bending modulus",
                  bending_modulus,
                  "Helfrich bending modulus κ [pN µm]; 0.2 pN µm is "
                  "2e-19 J.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Spontaneous curvature",
                  spontaneous_curvature,
                  "Spontaneous (total) curvature c0 of the Helfrich energy "
                  "κ/2 ∫ (2H - c0)² dA [1/µm]; 2H = 2/R on a sphere of "
                  "radius R with outward normals.",
                  Patterns::Double());
    add_parameter(prm,
                  "Area penalty",
                  area_penalty,
                  "k_A of the global area energy k_A/2 (A - A0)²/A0 "
                  "[pN/µm].",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Volume penalty",
                  volume_penalty,
                  "k_V of the global volume energy k_V/2 (V - V0)²/V0 "
                  "[pN/µm²].",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Finite element degree",
                  degree,
                  "Degree k of the membrane's FESystem<2,3>(FE_Q<2,3>(k), "
                  "3) position field.",
                  Patterns::Integer(1, 2));
    prm.leave_subsection();
  }

  void
  MembraneParameters::validate() const
  {
    make_elastic_law(law, shear_modulus, area_dilation_modulus);
  }
} // namespace rbc_ifem

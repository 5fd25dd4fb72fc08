#ifndef rbc_ifem_membrane_elastic_law_h
#define rbc_ifem_membrane_elastic_law_h

#include <string>
#include <variant>
#include <vector>

namespace rbc_ifem
{
  /**
   * The in-plane hyperelastic laws of the membrane (Membrane/Elastic law).
   * Each is a type with its name as the parameter file spells it, a
   * constructor that takes the small-strain shear modulus G and area
   * dilation modulus K [pN/µm] (and throws InputError, naming
   * Membrane/Area dilation modulus, if the law cannot have them), and the
   * strain energy density W(I1, J) per reference area [pN/µm] in the
   * invariants I1 = λ1² + λ2² and J = λ1 λ2 of the surface Cauchy-Green
   * tensor, for any number type: the membrane forces differentiate it with
   * Sacado (Membrane).
   *
   * A new law is a struct like these, added to ElasticLaw.
   */

  /**
   * The paper's law, the incompressible thin-shell form with λ3 = 1/(λ1 λ2)
   * plus an area term: W = C1 (I1 + 1/J² - 3) + C2/2 (J - 1)², with
   * C1 = G/2 and C2 = K - 3G, which give the small-strain moduli G and K.
   */
  struct NeoHookean
  {
    static constexpr const char *name = "neo-Hookean";

    NeoHookean(const double shear_modulus, const double area_dilation_modulus);

    template <typename Number>
    Number
    energy_density(const Number &I1, const Number &J) const
    {
      return C1 * (I1 + 1. / (J * J) - 3.) + C2 / 2. * (J - 1.) * (J - 1.);
    }

    double C1, C2;
  };

  /**
   * Skalak et al. (1973): W = G/4 (I1'² + 2 I1' - 2 I2' + C I2'²), with
   * I1' = I1 - 2, I2' = J² - 1 and C = (K/G - 1)/2.
   */
  struct Skalak
  {
    static constexpr const char *name = "Skalak";

    Skalak(const double shear_modulus, const double area_dilation_modulus);

    template <typename Number>
    Number
    energy_density(const Number &I1, const Number &J) const
    {
      const Number I1s = I1 - 2.;
      const Number I2s = J * J - 1.;
      return G / 4. * (I1s * I1s + 2. * I1s - 2. * I2s + C * I2s * I2s);
    }

    double G, C;
  };

  /// One of the laws; a Membrane holds the one its parameters name.
  using ElasticLaw = std::variant<NeoHookean, Skalak>;

  /// The name of every law of ElasticLaw, in its order.
  std::vector<std::string>
  elastic_law_names();

  /**
   * The law called @p name with the moduli @p shear_modulus and
   * @p area_dilation_modulus; throws InputError if it cannot have them.
   */
  ElasticLaw
  make_elastic_law(const std::string &name,
                   const double       shear_modulus,
                   const double       area_dilation_modulus);
} // namespace rbc_ifem

#endif

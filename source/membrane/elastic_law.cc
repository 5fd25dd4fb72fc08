#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/membrane/elastic_law.h>

#include <stdexcept>
#include <utility>

namespace rbc_ifem
{
  NeoHookean::NeoHookean(const double G, const double K)
    : C1(G / 2.)
    , C2(K - 3. * G)
  {
    // K = 3G is allowed; moduli scaled by one factor (the shear experiment)
    // may land an ulp below it.
    if (!(K >= 3. * G * (1. - 1e-12)))
      throw InputError("Membrane/Area dilation modulus",
                       to_text(K),
                       "the neo-Hookean law needs K ≥ 3 G = " +
                         to_text(3. * G) +
                         " pN/µm (its C2 = K - 3G; K = 3G is the classical "
                         "thin-shell law).");
  }

  Skalak::Skalak(const double G, const double K)
    : G(G)
    , C((K / G - 1.) / 2.)
  {
    if (!(K > G))
      throw InputError("Membrane/Area dilation modulus",
                       to_text(K),
                       "the Skalak law needs K > G = " + to_text(G) +
                         " pN/µm (its C = (K/G - 1)/2 > 0).");
  }

  namespace
  {
    template <std::size_t... I>
    std::vector<std::string>
    names(std::index_sequence<I...>)
    {
      return {std::variant_alternative_t<I, ElasticLaw>::name...};
    }

    /// The law of ElasticLaw named @p name, searched from alternative I on.
    template <std::size_t I = 0>
    ElasticLaw
    law_named(const std::string &name, const double G, const double K)
    {
      if constexpr (I == std::variant_size_v<ElasticLaw>)
        throw std::logic_error("no elastic law is named '" + name + "'");
      else
        {
          using Law = std::variant_alternative_t<I, ElasticLaw>;
          if (name == Law::name)
            return Law(G, K);
          return law_named<I + 1>(name, G, K);
        }
    }
  } // namespace

  std::vector<std::string>
  elastic_law_names()
  {
    return names(std::make_index_sequence<std::variant_size_v<ElasticLaw>>());
  }

  ElasticLaw
  make_elastic_law(const std::string &name,
                   const double       shear_modulus,
                   const double       area_dilation_modulus)
  {
    return law_named(name, shear_modulus, area_dilation_modulus);
  }
} // namespace rbc_ifem

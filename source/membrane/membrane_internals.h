#ifndef rbc_ifem_membrane_membrane_internals_h
#define rbc_ifem_membrane_membrane_internals_h

// What the two halves of class Membrane share, its energy and forces
// (membrane.cc) and its tangent stiffness (membrane_stiffness.cc): the
// point-level terms of the energy, the sums they make and the sharing of
// work over ranks. Private to those files, so not under include/.

#include <rbc_ifem/base/ranks.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>
#include <deal.II/differentiation/ad/sacado_product_types.h>

#include <Sacado.hpp>

#include <array>
#include <vector>

// deal.II 9.4 knows the product types of Sacado's DFad, not of the
// fixed-length SFad the membrane forces use: declare them, so that Tensor
// arithmetic on SFad (cross products, contractions) gives SFad.
DEAL_II_NAMESPACE_OPEN
namespace internal
{
  template <typename T, int N>
  struct ProductTypeImpl<Sacado::Fad::SFad<T, N>, double>
  {
    using type = Sacado::Fad::SFad<T, N>;
  };

  template <typename T, int N>
  struct ProductTypeImpl<double, Sacado::Fad::SFad<T, N>>
  {
    using type = Sacado::Fad::SFad<T, N>;
  };

  template <typename T, int N>
  struct ProductTypeImpl<Sacado::Fad::SFad<T, N>, Sacado::Fad::SFad<T, N>>
  {
    using type = Sacado::Fad::SFad<T, N>;
  };
} // namespace internal

template <typename T, int N>
struct EnableIfScalar<Sacado::Fad::SFad<T, N>>
{
  using type = Sacado::Fad::SFad<T, N>;
};
DEAL_II_NAMESPACE_CLOSE

namespace rbc_ifem
{
  /// The cell terms summed over the membrane.
  struct Membrane::Sums
  {
    double                    in_plane = 0., area = 0., volume = 0.;
    std::vector<Tensor<1, 3>> laplacian, normal;
    std::vector<double>       mass;
  };

  /// dE/d(sum) for every sum of Sums (the in-plane sum's is 1).
  struct Membrane::Multipliers
  {
    double                    area = 0., volume = 0.;
    std::vector<Tensor<1, 3>> laplacian, normal;
    std::vector<double>       mass;
  };

  namespace MembraneInternals
  {
    /// Replace @p values on every rank of @p comm by their sum over the ranks.
    inline void
    add_up_over_ranks(const ArrayView<double> &values, const MPI_Comm comm)
    {
      Utilities::MPI::sum(ArrayView<const double>(values.data(), values.size()),
                          comm,
                          values);
    }

    /// The surface at one quadrature point, from its tangents.
    template <typename Number>
    struct SurfacePoint
    {
      Tensor<2, 2, Number> g_inverse; ///< the inverse metric g^{αβ}
      Number               I1;        ///< tr(G⁻¹g) = λ1² + λ2²
      Number               J;         ///< λ1λ2 = dA/dA0
      Number               dA;        ///< sqrt(det g) times the weight
      Tensor<1, 3, Number> normal_dA; ///< t0 × t1 times the weight
    };

    /**
     * SurfacePoint of the tangents @p tangent at a quadrature point of
     * weight @p w, whose reference surface has the inverse metric
     * @p G_inverse and the area element @p reference_jacobian.
     */
    template <typename Number>
    SurfacePoint<Number>
    surface_point(const Tensor<1, 3, Number> (&tangent)[2],
                  const Tensor<2, 2> &G_inverse,
                  const double        reference_jacobian,
                  const double        w)
    {
      using std::sqrt;
      Tensor<2, 2, Number> g;
      for (unsigned int alpha = 0; alpha < 2; ++alpha)
        for (unsigned int beta = 0; beta < 2; ++beta)
          g[alpha][beta] = tangent[alpha] * tangent[beta];
      SurfacePoint<Number> point;
      point.g_inverse       = invert(g);
      const Number jacobian = sqrt(determinant(g));
      point.I1              = 0.;
      for (unsigned int alpha = 0; alpha < 2; ++alpha)
        for (unsigned int beta = 0; beta < 2; ++beta)
          point.I1 += G_inverse[alpha][beta] * g[alpha][beta];
      point.J         = jacobian / reference_jacobian;
      point.dA        = jacobian * w;
      point.normal_dA = cross_product_3d(tangent[0], tangent[1]) * w;
      return point;
    }
  } // namespace MembraneInternals

  /**
   * The derivatives of E by the sums, gathered at one quadrature point:
   * the integrand of cell_potential() there is point_potential().
   */
  struct Membrane::PointWeights
  {
    double       area = 0., volume = 0.; ///< d_A, d_V
    double       mass = 0.;              ///< Σ_a d_m N_a
    Tensor<1, 3> normal;                 ///< Σ_a d_w N_a
    Tensor<1, 3> laplacian[2];           ///< Σ_a d_y ∂_α N_a
  };

  template <typename Number, typename Law>
  Number
  Membrane::point_potential(const Law                   &law,
                            const unsigned int           c,
                            const unsigned int           q,
                            const std::array<Number, 9> &z,
                            const PointWeights          &weights) const
  {
    Tensor<1, 3, Number> position, tangent[2];
    for (unsigned int d = 0; d < 3; ++d)
      {
        position[d]   = z[d];
        tangent[0][d] = z[3 + d];
        tangent[1][d] = z[6 + d];
      }
    const double                                  w = quadrature.weight(q);
    const ReferenceMetric                        &G = reference_metric();
    const MembraneInternals::SurfacePoint<Number> point =
      MembraneInternals::surface_point(tangent,
                                       G.inverse[c][q],
                                       G.jacobian[c][q],
                                       w);
    Number phi = law.energy_density(point.I1, point.J) * G.jacobian[c][q] * w +
                 (weights.area + weights.mass) * point.dA +
                 weights.volume / 3. * (position * point.normal_dA) +
                 weights.normal * point.normal_dA;
    for (unsigned int alpha = 0; alpha < 2; ++alpha)
      for (unsigned int beta = 0; beta < 2; ++beta)
        phi += point.g_inverse[alpha][beta] * point.dA *
               (weights.laplacian[alpha] * tangent[beta]);
    return phi;
  }
} // namespace rbc_ifem

#endif

#include <rbc_ifem/base/output.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/base/mpi.h>
#include <deal.II/differentiation/ad/sacado_product_types.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_fe_field.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/data_out.h>

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

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
  /// What one cell contributes, at positions of type Number.
  template <typename Number>
  struct Membrane::CellTerms
  {
    Number                            in_plane = 0.;
    Number                            area     = 0.;
    Number                            volume   = 0.;
    std::vector<Tensor<1, 3, Number>> laplacian; ///< y_a = ∫ ∇_Γ N_a · ∇_Γ x dA
    std::vector<Number>               mass;   ///< m_a = ∫ N_a dA
    std::vector<Tensor<1, 3, Number>> normal; ///< ∫ N_a n dA
  };

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

  namespace
  {
    /// The number of ranks of @p comm; 1 in a program that never started
    /// MPI (a serial test).
    unsigned int
    n_ranks(const MPI_Comm comm)
    {
      return Utilities::MPI::job_supports_mpi() ?
               Utilities::MPI::n_mpi_processes(comm) :
               1;
    }

    /// Replace @p values on every rank of @p comm by their sum over the ranks.
    void
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

    /**
     * The bending energy of one node from its sums, κ/2 m |y/m - c0 ν|²
     * with ν = w/|w| (Membrane): for any number type, so that its Hessian
     * in (y, m, w) can be taken with Sacado.
     */
    template <typename Number>
    Number
    nodal_bending_energy(const Tensor<1, 3, Number> &y,
                         const Number               &m,
                         const Tensor<1, 3, Number> &w,
                         const double                kappa,
                         const double                c0)
    {
      using std::sqrt;
      const Number               norm_w = sqrt(w * w);
      const Tensor<1, 3, Number> u      = y / m - c0 * w / norm_w;
      return kappa / 2. * m * (u * u);
    }

    /// The Hessian of nodal_bending_energy() in (y, m, w), 7 × 7.
    FullMatrix<double>
    nodal_bending_hessian(const Tensor<1, 3> &y,
                          const double        m,
                          const Tensor<1, 3> &w,
                          const double        kappa,
                          const double        c0)
    {
      using First  = Sacado::Fad::SFad<double, 7>;
      using Second = Sacado::Fad::SFad<First, 7>;
      const std::array<double, 7> values{
        {y[0], y[1], y[2], m, w[0], w[1], w[2]}};
      std::array<Second, 7> s;
      for (unsigned int j = 0; j < 7; ++j)
        s[j] = Second(7, j, First(7, j, values[j]));
      const Tensor<1, 3, Second> Y({s[0], s[1], s[2]}), W({s[4], s[5], s[6]});
      const Second       e = nodal_bending_energy(Y, s[3], W, kappa, c0);
      FullMatrix<double> hessian(7, 7);
      for (unsigned int j = 0; j < 7; ++j)
        for (unsigned int l = 0; l < 7; ++l)
          hessian(j, l) = e.dx(j).dx(l);
      return hessian;
    }
  } // namespace

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

  void
  MembraneStiffness::vmult_add(Vector<double>       &dst,
                               const Vector<double> &src) const
  {
    if (n_ranks(communicator) == 1)
      local.vmult_add(dst, src);
    else
      {
        // Each rank holds its share of the sparse part: sum the products.
        Vector<double> product(dst.size());
        local.vmult(product, src);
        add_up_over_ranks(make_array_view(product), communicator);
        dst += product;
      }
    for (const auto &[c, gradient] : rank_one)
      dst.add(c * (gradient * src), gradient);
  }

  Membrane::Membrane(const Triangulation<2, 3> &reference_mesh,
                     const MembraneParameters  &parameters)
    : parameters(parameters)
    , elastic_law(make_elastic_law(parameters.law,
                                   parameters.shear_modulus,
                                   parameters.area_dilation_modulus))
    , scalar_fe(parameters.degree)
    , fe(scalar_fe, 3)
    , dof_handler(reference_mesh)
    , quadrature(parameters.degree + 2)
  {
    dof_handler.distribute_dofs(fe);

    const unsigned int n_q = quadrature.size(),
                       n_a = scalar_fe.n_dofs_per_cell();
    shape_values.reinit(n_a, n_q);
    shape_gradients.reinit(n_a, n_q);
    for (unsigned int a = 0; a < n_a; ++a)
      for (unsigned int q = 0; q < n_q; ++q)
        {
          shape_values(a, q)    = scalar_fe.shape_value(a, quadrature.point(q));
          shape_gradients(a, q) = scalar_fe.shape_grad(a, quadrature.point(q));
        }
    point_maps.assign(n_q, FullMatrix<double>(9, fe.n_dofs_per_cell()));
    for (unsigned int q = 0; q < n_q; ++q)
      for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
        {
          const auto [e, a]       = fe.system_to_component_index(k);
          point_maps[q](e, k)     = shape_values(a, q);
          point_maps[q](3 + e, k) = shape_gradients(a, q)[0];
          point_maps[q](6 + e, k) = shape_gradients(a, q)[1];
        }

    // Nodes: numbered by the DoF of their x component.
    std::vector<int> node_of_dof(dof_handler.n_dofs(), -1);
    component_of_dof.resize(dof_handler.n_dofs());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        cell->get_dof_indices(dofs);
        std::vector<unsigned int> nodes(n_a);
        for (unsigned int k = 0; k < dofs.size(); ++k)
          component_of_dof[dofs[k]] = fe.system_to_component_index(k).first;
        for (unsigned int a = 0; a < n_a; ++a)
          {
            const auto first = dofs[fe.component_to_system_index(0, a)];
            if (node_of_dof[first] < 0)
              {
                node_of_dof[first] = n_nodes++;
                node_dofs.push_back(
                  {{first,
                    dofs[fe.component_to_system_index(1, a)],
                    dofs[fe.component_to_system_index(2, a)]}});
              }
            nodes[a] = node_of_dof[first];
          }
        cell_dofs.push_back(dofs);
        cell_nodes.push_back(nodes);
      }

    // The stiffness couples the DoFs of all cells around a node: the
    // bending energy of a node depends on them through its sums.
    cells_around_node.resize(n_nodes);
    for (unsigned int c = 0; c < cell_nodes.size(); ++c)
      for (unsigned int a = 0; a < n_a; ++a)
        cells_around_node[cell_nodes[c][a]].emplace_back(c, a);
    DynamicSparsityPattern coupled(dof_handler.n_dofs());
    for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const std::vector<types::global_dof_index> patch = patch_dofs(i);
        for (const types::global_dof_index row : patch)
          coupled.add_entries(row, patch.begin(), patch.end(), true);
      }
    stiffness_sparsity.copy_from(coupled);

    // X: the support points of the field, on the curved reference surface.
    const MappingQ<2, 3> mapping(std::max(2u, parameters.degree));
    std::map<types::global_dof_index, Point<3>> support_points;
    DoFTools::map_dofs_to_support_points(mapping, dof_handler, support_points);
    reference.reinit(dof_handler.n_dofs());
    for (const auto &[dof, point] : support_points)
      reference[dof] = point[component(dof)];

    for (unsigned int c = 0; c < cell_dofs.size(); ++c)
      {
        const std::vector<double> X = local_positions(c, reference);
        reference_metric_inverse.emplace_back(n_q);
        reference_jacobian.emplace_back(n_q);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            Tensor<1, 3> tangent[2];
            for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
              {
                const auto [d, a] = fe.system_to_component_index(k);
                for (unsigned int alpha = 0; alpha < 2; ++alpha)
                  tangent[alpha][d] += X[k] * shape_gradients(a, q)[alpha];
              }
            Tensor<2, 2> metric;
            for (unsigned int alpha = 0; alpha < 2; ++alpha)
              for (unsigned int beta = 0; beta < 2; ++beta)
                metric[alpha][beta] = tangent[alpha] * tangent[beta];
            reference_metric_inverse[c][q] = invert(metric);
            reference_jacobian[c][q]       = std::sqrt(determinant(metric));
          }
      }
    for (unsigned int c = 0; c < cell_dofs.size(); ++c)
      {
        reference_cell_areas.push_back(0.);
        for (unsigned int q = 0; q < n_q; ++q)
          reference_cell_areas[c] +=
            reference_jacobian[c][q] * quadrature.weight(q);
      }
    area0   = area(reference);
    volume0 = volume(reference);
  }

  const DoFHandler<2, 3> &
  Membrane::get_dof_handler() const
  {
    return dof_handler;
  }

  const Vector<double> &
  Membrane::reference_positions() const
  {
    return reference;
  }

  const std::vector<std::array<types::global_dof_index, 3>> &
  Membrane::nodes() const
  {
    return node_dofs;
  }

  unsigned int
  Membrane::component(const types::global_dof_index dof) const
  {
    return component_of_dof[dof];
  }

  std::vector<double>
  Membrane::local_positions(const unsigned int    cell,
                            const Vector<double> &x) const
  {
    std::vector<double> local(cell_dofs[cell].size());
    for (unsigned int k = 0; k < local.size(); ++k)
      local[k] = x[cell_dofs[cell][k]];
    return local;
  }

  template <typename Number, typename Law>
  Membrane::CellTerms<Number>
  Membrane::cell_terms(const Law                 &law,
                       const unsigned int         cell,
                       const std::vector<Number> &x) const
  {
    const unsigned int n_a = scalar_fe.n_dofs_per_cell();
    CellTerms<Number>  terms;
    terms.laplacian.resize(n_a);
    terms.mass.resize(n_a);
    terms.normal.resize(n_a);

    for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        Tensor<1, 3, Number> position, tangent[2];
        for (unsigned int k = 0; k < x.size(); ++k)
          {
            const auto [d, a] = fe.system_to_component_index(k);
            position[d] += x[k] * shape_values(a, q);
            for (unsigned int alpha = 0; alpha < 2; ++alpha)
              tangent[alpha][d] += x[k] * shape_gradients(a, q)[alpha];
          }
        const double               w = quadrature.weight(q);
        const SurfacePoint<Number> point =
          surface_point(tangent,
                        reference_metric_inverse[cell][q],
                        reference_jacobian[cell][q],
                        w);
        const Number               &dA        = point.dA;
        const Tensor<1, 3, Number> &normal_dA = point.normal_dA;
        terms.in_plane += law.energy_density(point.I1, point.J) *
                          reference_jacobian[cell][q] * w;
        terms.area += dA;
        terms.volume += position * normal_dA / 3.;
        for (unsigned int a = 0; a < n_a; ++a)
          {
            terms.mass[a] += shape_values(a, q) * dA;
            terms.normal[a] += shape_values(a, q) * normal_dA;
            // ∇_Γ N_a · ∇_Γ x = g^{αβ} ∂_α N_a ∂_β x
            for (unsigned int alpha = 0; alpha < 2; ++alpha)
              for (unsigned int beta = 0; beta < 2; ++beta)
                {
                  const Number weight = point.g_inverse[alpha][beta] *
                                        shape_gradients(a, q)[alpha] * dA;
                  terms.laplacian[a] += weight * tangent[beta];
                }
          }
      }
    return terms;
  }

  Membrane::Sums
  Membrane::sum_cell_terms(
    const Vector<double>                       &x,
    const std::pair<unsigned int, unsigned int> cells) const
  {
    Sums sums;
    sums.laplacian.resize(n_nodes);
    sums.normal.resize(n_nodes);
    sums.mass.resize(n_nodes);
    // The law is chosen once per call, outside the loop over the cells.
    std::visit(
      [&](const auto &law) {
        for (unsigned int c = cells.first; c < cells.second; ++c)
          add_cell_terms(c, cell_terms(law, c, local_positions(c, x)), sums);
      },
      elastic_law);
    return sums;
  }

  Membrane::Sums
  Membrane::sum_cell_terms(const Vector<double> &x) const
  {
    return sum_cell_terms(x, {0, cell_dofs.size()});
  }

  Membrane::Sums
  Membrane::sum_shared_cell_terms(const Vector<double> &x) const
  {
    Sums sums = sum_cell_terms(x, share(cell_dofs.size()));
    if (n_ranks(communicator) == 1)
      return sums;
    // One reduction for all sums, packed in one array.
    std::vector<double> packed{sums.in_plane, sums.area, sums.volume};
    packed.reserve(3 + 7 * n_nodes);
    for (unsigned int i = 0; i < n_nodes; ++i)
      {
        for (unsigned int e = 0; e < 3; ++e)
          packed.insert(packed.end(),
                        {sums.laplacian[i][e], sums.normal[i][e]});
        packed.push_back(sums.mass[i]);
      }
    add_up_over_ranks(make_array_view(packed), communicator);
    auto value    = packed.begin();
    sums.in_plane = *value++;
    sums.area     = *value++;
    sums.volume   = *value++;
    for (unsigned int i = 0; i < n_nodes; ++i)
      {
        for (unsigned int e = 0; e < 3; ++e)
          {
            sums.laplacian[i][e] = *value++;
            sums.normal[i][e]    = *value++;
          }
        sums.mass[i] = *value++;
      }
    return sums;
  }

  std::pair<unsigned int, unsigned int>
  Membrane::share(const unsigned int n) const
  {
    const unsigned int size = n_ranks(communicator),
                       rank = size == 1 ?
                                0 :
                                Utilities::MPI::this_mpi_process(communicator);
    return {static_cast<unsigned int>(std::uint64_t(n) * rank / size),
            static_cast<unsigned int>(std::uint64_t(n) * (rank + 1) / size)};
  }

  void
  Membrane::share_work(const MPI_Comm comm)
  {
    communicator = comm;
  }

  void
  Membrane::add_cell_terms(const unsigned int       c,
                           const CellTerms<double> &terms,
                           Sums                    &sums) const
  {
    sums.in_plane += terms.in_plane;
    sums.area += terms.area;
    sums.volume += terms.volume;
    for (unsigned int a = 0; a < cell_nodes[c].size(); ++a)
      {
        const unsigned int i = cell_nodes[c][a];
        sums.laplacian[i] += terms.laplacian[a];
        sums.normal[i] += terms.normal[a];
        sums.mass[i] += terms.mass[a];
      }
  }

  MembraneEnergy
  Membrane::energy(const Vector<double> &x) const
  {
    Vector<double> no_forces;
    return energy_and_forces(x, no_forces);
  }

  Membrane::Multipliers
  Membrane::energy_derivatives(const Sums &sums, MembraneEnergy &energy) const
  {
    const double kappa = parameters.bending_modulus,
                 c0    = parameters.spontaneous_curvature;
    Multipliers d;
    energy.in_plane = sums.in_plane;
    // The penalties, and their derivatives by the sums A and V. A switched
    // off penalty is left out, so that open test patches (V0 = 0) work.
    if (parameters.area_penalty > 0.)
      {
        energy.area =
          parameters.area_penalty / 2. * std::pow(sums.area - area0, 2) / area0;
        d.area = parameters.area_penalty * (sums.area - area0) / area0;
      }
    if (parameters.volume_penalty > 0.)
      {
        energy.volume = parameters.volume_penalty / 2. *
                        std::pow(sums.volume - volume0, 2) / volume0;
        d.volume =
          parameters.volume_penalty * (sums.volume - volume0) / volume0;
      }

    // The bending energy κ/2 Σ m_i |u_i|², u_i = y_i/m_i - c0 ν_i, and its
    // derivatives by the nodal sums y_i, m_i and w_i = ∫ N_i n dA.
    d.laplacian.resize(n_nodes);
    d.normal.resize(n_nodes);
    d.mass.resize(n_nodes);
    for (unsigned int i = 0; i < n_nodes; ++i)
      {
        const double       m  = sums.mass[i];
        const double       w  = sums.normal[i].norm();
        const Tensor<1, 3> nu = sums.normal[i] / w;
        const Tensor<1, 3> u  = sums.laplacian[i] / m - c0 * nu;
        energy.bending += kappa / 2. * m * (u * u);
        d.laplacian[i] = kappa * u;
        d.mass[i] = kappa / 2. * (u * u) - kappa * (u * sums.laplacian[i]) / m;
        d.normal[i] = -kappa * c0 * m / w * (u - (u * nu) * nu);
      }
    return d;
  }

  MembraneEnergy
  Membrane::energy_and_forces(const Vector<double> &x,
                              Vector<double>       &forces) const
  {
    MembraneEnergy    energy;
    const Multipliers d = energy_derivatives(sum_shared_cell_terms(x), energy);
    if (forces.size() == 0)
      return energy;

    // F = -dE/dx: per cell, the derivative of its potential φ_c
    // (cell_potential()), whose gradient is E's. φ_c's integrand depends on
    // the DoFs only through the point's position and tangents z = L_q x, so
    // ∂φ_c/∂x = Σ_q L_qᵀ ∂φ_q/∂z, with the 9 derivatives by forward mode:
    // far cheaper than forward mode in the cell's DoFs.
    forces                              = 0.;
    const auto subtract_point_gradients = [&](const auto &law) {
      using ADNumber = Sacado::Fad::SFad<double, 9>;
      Vector<double> values(fe.n_dofs_per_cell()), z(9), dphi_dz(9),
        gradient(fe.n_dofs_per_cell());
      const auto [begin, end] = share(cell_dofs.size());
      for (unsigned int c = begin; c < end; ++c)
        {
          x.extract_subvector_to(cell_dofs[c].begin(),
                                 cell_dofs[c].end(),
                                 values.begin());
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              point_maps[q].vmult(z, values);
              std::array<ADNumber, 9> z_ad;
              for (unsigned int j = 0; j < 9; ++j)
                z_ad[j] = ADNumber(9, j, z[j]);
              const ADNumber phi =
                point_potential(law, c, q, z_ad, point_weights(c, q, d));
              for (unsigned int j = 0; j < 9; ++j)
                dphi_dz[j] = phi.dx(j);
              point_maps[q].Tvmult(gradient, dphi_dz);
              for (unsigned int k = 0; k < gradient.size(); ++k)
                forces[cell_dofs[c][k]] -= gradient[k];
            }
        }
    };
    std::visit(subtract_point_gradients, elastic_law);
    if (n_ranks(communicator) > 1)
      add_up_over_ranks(make_array_view(forces), communicator);
    return energy;
  }

  template <typename Number>
  Number
  Membrane::cell_potential(const unsigned int       c,
                           const CellTerms<Number> &terms,
                           const Multipliers       &d) const
  {
    Number phi = terms.in_plane + d.area * terms.area + d.volume * terms.volume;
    for (unsigned int a = 0; a < cell_nodes[c].size(); ++a)
      {
        const unsigned int i = cell_nodes[c][a];
        phi += d.laplacian[i] * terms.laplacian[a] + d.mass[i] * terms.mass[a] +
               d.normal[i] * terms.normal[a];
      }
    return phi;
  }

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
    const double               w     = quadrature.weight(q);
    const SurfacePoint<Number> point = surface_point(
      tangent, reference_metric_inverse[c][q], reference_jacobian[c][q], w);
    Number phi =
      law.energy_density(point.I1, point.J) * reference_jacobian[c][q] * w +
      (weights.area + weights.mass) * point.dA +
      weights.volume / 3. * (position * point.normal_dA) +
      weights.normal * point.normal_dA;
    for (unsigned int alpha = 0; alpha < 2; ++alpha)
      for (unsigned int beta = 0; beta < 2; ++beta)
        phi += point.g_inverse[alpha][beta] * point.dA *
               (weights.laplacian[alpha] * tangent[beta]);
    return phi;
  }

  template <typename Number>
  auto
  Membrane::point_integrands(const unsigned int           c,
                             const unsigned int           q,
                             const std::array<Number, 9> &z) const
    -> std::array<Number, n_point_integrands>
  {
    Tensor<1, 3, Number> position, tangent[2];
    for (unsigned int e = 0; e < 3; ++e)
      {
        position[e]   = z[e];
        tangent[0][e] = z[3 + e];
        tangent[1][e] = z[6 + e];
      }
    const SurfacePoint<Number> point =
      surface_point(tangent,
                    reference_metric_inverse[c][q],
                    reference_jacobian[c][q],
                    quadrature.weight(q));
    std::array<Number, n_point_integrands> t;
    t[0] = point.dA;
    t[1] = position * point.normal_dA / 3.;
    for (unsigned int e = 0; e < 3; ++e)
      t[2 + e] = point.normal_dA[e];
    // g^{αβ} t_β dA: ∂_α N_a times it is the integrand of y_a.
    for (unsigned int alpha = 0; alpha < 2; ++alpha)
      for (unsigned int e = 0; e < 3; ++e)
        {
          t[5 + 3 * alpha + e] = 0.;
          for (unsigned int beta = 0; beta < 2; ++beta)
            t[5 + 3 * alpha + e] +=
              point.g_inverse[alpha][beta] * point.dA * tangent[beta][e];
        }
    return t;
  }

  Membrane::PointWeights
  Membrane::point_weights(const unsigned int c,
                          const unsigned int q,
                          const Multipliers &d) const
  {
    PointWeights weights;
    weights.area   = d.area;
    weights.volume = d.volume;
    for (unsigned int a = 0; a < cell_nodes[c].size(); ++a)
      {
        const unsigned int i = cell_nodes[c][a];
        weights.mass += d.mass[i] * shape_values(a, q);
        weights.normal += shape_values(a, q) * d.normal[i];
        for (unsigned int alpha = 0; alpha < 2; ++alpha)
          weights.laplacian[alpha] +=
            shape_gradients(a, q)[alpha] * d.laplacian[i];
      }
    return weights;
  }

  std::vector<types::global_dof_index>
  Membrane::patch_dofs(const unsigned int i) const
  {
    std::vector<types::global_dof_index> patch;
    for (const auto &[c, a] : cells_around_node[i])
      patch.insert(patch.end(), cell_dofs[c].begin(), cell_dofs[c].end());
    std::sort(patch.begin(), patch.end());
    patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
    return patch;
  }

  void
  Membrane::stiffness(const Vector<double> &x, MembraneStiffness &K) const
  {
    const Sums        sums = sum_shared_cell_terms(x);
    MembraneEnergy    energy;
    const Multipliers d = energy_derivatives(sums, energy);
    K.local.reinit(stiffness_sparsity);
    K.rank_one.clear();
    K.communicator = communicator;

    // Every integrand depends on the DoFs only through the point's position
    // and tangents z = L_q x (9 numbers), so derivatives in the cell's DoFs
    // are taken in z, by forward mode per point, and chained with L_q: far
    // cheaper than forward mode over the cell.
    //
    // First, per cell, the first derivatives of its terms: of A and V for
    // the penalties' rank-one parts (this rank's cells, summed over the
    // ranks) and of each node's sums (y, m, w: 7 rows per local node) for
    // the bending chain below (the cells around this rank's nodes).
    const unsigned int n_a            = scalar_fe.n_dofs_per_cell(),
                       n              = fe.n_dofs_per_cell();
    const auto [first_cell, end_cell] = share(cell_dofs.size());
    const auto [first_node, end_node] = share(n_nodes);
    std::vector<bool> needed(cell_dofs.size(), false);
    std::fill(needed.begin() + first_cell, needed.begin() + end_cell, true);
    for (unsigned int i = first_node; i < end_node; ++i)
      for (const auto &[c, a] : cells_around_node[i])
        needed[c] = true;
    Vector<double> area_gradient(dof_handler.n_dofs()),
      volume_gradient(dof_handler.n_dofs());
    std::vector<FullMatrix<double>> sum_derivatives(cell_dofs.size());
    {
      using First = Sacado::Fad::SFad<double, 9>;
      FullMatrix<double> D(n_point_integrands, 9), DL(n_point_integrands, n);
      Vector<double>     values(n), z(9);
      for (unsigned int c = 0; c < cell_dofs.size(); ++c)
        {
          if (!needed[c])
            continue;
          const bool own = c >= first_cell && c < end_cell;
          x.extract_subvector_to(cell_dofs[c].begin(),
                                 cell_dofs[c].end(),
                                 values.begin());
          FullMatrix<double> &J = sum_derivatives[c];
          J.reinit(7 * n_a, n);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              point_maps[q].vmult(z, values);
              std::array<First, 9> z1;
              for (unsigned int j = 0; j < 9; ++j)
                z1[j] = First(9, j, z[j]);
              const auto t = point_integrands(c, q, z1);
              for (unsigned int r = 0; r < n_point_integrands; ++r)
                for (unsigned int j = 0; j < 9; ++j)
                  D(r, j) = t[r].dx(j);
              D.mmult(DL, point_maps[q]);
              for (unsigned int k = 0; k < n; ++k)
                {
                  if (own)
                    {
                      area_gradient[cell_dofs[c][k]] += DL(0, k);
                      volume_gradient[cell_dofs[c][k]] += DL(1, k);
                    }
                  for (unsigned int a = 0; a < n_a; ++a)
                    {
                      const double N = shape_values(a, q);
                      J(7 * a + 3, k) += N * DL(0, k);
                      for (unsigned int e = 0; e < 3; ++e)
                        {
                          J(7 * a + 4 + e, k) += N * DL(2 + e, k);
                          for (unsigned int alpha = 0; alpha < 2; ++alpha)
                            J(7 * a + e, k) += shape_gradients(a, q)[alpha] *
                                               DL(5 + 3 * alpha + e, k);
                        }
                    }
                }
            }
        }
    }

    // The Hessian of each of this rank's cells' potentials φ_c
    // (cell_potential()), H_c = Σ_q L_qᵀ H_q L_q, with the 9 × 9 H_q by
    // nested forward mode.
    const auto add_cell_hessians = [&](const auto &law) {
      using First  = Sacado::Fad::SFad<double, 9>;
      using Second = Sacado::Fad::SFad<First, 9>;
      FullMatrix<double> cell_matrix(n, n), H(9, 9), HL(9, n);
      Vector<double>     values(n), z(9);
      for (unsigned int c = first_cell; c < end_cell; ++c)
        {
          x.extract_subvector_to(cell_dofs[c].begin(),
                                 cell_dofs[c].end(),
                                 values.begin());
          cell_matrix = 0.;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const FullMatrix<double> &L = point_maps[q];
              L.vmult(z, values);
              std::array<Second, 9> z2;
              for (unsigned int j = 0; j < 9; ++j)
                z2[j] = Second(9, j, First(9, j, z[j]));
              const Second phi =
                point_potential(law, c, q, z2, point_weights(c, q, d));
              for (unsigned int j = 0; j < 9; ++j)
                for (unsigned int l = 0; l < 9; ++l)
                  H(j, l) = phi.dx(j).dx(l);
              H.mmult(HL, L);
              L.Tmmult(cell_matrix, HL, /*adding=*/true);
            }
          K.local.add(cell_dofs[c], cell_matrix);
        }
    };
    std::visit(add_cell_hessians, elastic_law);
    if (n_ranks(communicator) > 1)
      {
        add_up_over_ranks(make_array_view(area_gradient), communicator);
        add_up_over_ranks(make_array_view(volume_gradient), communicator);
      }

    // The bending energy's curvature in each of this rank's nodes' sums
    // s_i = (y, m, w): J_iᵀ B_i J_i, with J_i = ∂s_i/∂x over the cells
    // around the node.
    for (unsigned int i = first_node; i < end_node; ++i)
      {
        const std::vector<types::global_dof_index> patch = patch_dofs(i);
        FullMatrix<double> J(7, patch.size()), BJ(7, patch.size()),
          patch_matrix(patch.size(), patch.size());
        for (const auto &[c, a] : cells_around_node[i])
          for (unsigned int k = 0; k < n; ++k)
            {
              const unsigned int column =
                std::lower_bound(patch.begin(), patch.end(), cell_dofs[c][k]) -
                patch.begin();
              for (unsigned int r = 0; r < 7; ++r)
                J(r, column) += sum_derivatives[c](7 * a + r, k);
            }
        nodal_bending_hessian(sums.laplacian[i],
                              sums.mass[i],
                              sums.normal[i],
                              parameters.bending_modulus,
                              parameters.spontaneous_curvature)
          .mmult(BJ, J);
        J.Tmmult(patch_matrix, BJ);
        K.local.add(patch, patch_matrix);
      }

    if (parameters.area_penalty > 0.)
      K.rank_one.emplace_back(parameters.area_penalty / area0, area_gradient);
    if (parameters.volume_penalty > 0.)
      K.rank_one.emplace_back(parameters.volume_penalty / volume0,
                              volume_gradient);
  }

  std::vector<double>
  Membrane::nodal_areas(const Vector<double> &x) const
  {
    return sum_cell_terms(x).mass;
  }

  std::vector<Tensor<1, 3>>
  Membrane::nodal_vector_areas(const Vector<double> &x) const
  {
    return sum_cell_terms(x).normal;
  }

  Vector<double>
  Membrane::local_area_changes(const Vector<double> &x) const
  {
    Vector<double> changes(cell_dofs.size());
    std::visit(
      [&](const auto &law) {
        for (unsigned int c = 0; c < cell_dofs.size(); ++c)
          changes[c] = cell_terms(law, c, local_positions(c, x)).area /
                         reference_cell_areas[c] -
                       1.;
      },
      elastic_law);
    return changes;
  }

  double
  Membrane::area(const Vector<double> &x) const
  {
    return sum_cell_terms(x).area;
  }

  double
  Membrane::volume(const Vector<double> &x) const
  {
    return sum_cell_terms(x).volume;
  }

  double
  Membrane::reference_area() const
  {
    return area0;
  }

  double
  Membrane::reference_volume() const
  {
    return volume0;
  }

  void
  Membrane::write_vtu(
    const Vector<double>                                      &x,
    const std::string                                         &directory,
    const std::string                                         &name,
    const std::vector<std::pair<std::string, Vector<double>>> &dof_vectors,
    const FieldData                                           &field_data) const
  {
    Vector<double> displacement(x);
    displacement -= reference;
    const MappingFEField<2, 3, Vector<double>> mapping(dof_handler, x);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(3, DataComponentInterpretation::component_is_part_of_vector);
    DataOut<2, 3> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(displacement,
                             std::vector<std::string>(3, "displacement"),
                             DataOut<2, 3>::type_dof_data,
                             vector_field);
    for (const auto &[field_name, values] : dof_vectors)
      data_out.add_data_vector(values,
                               std::vector<std::string>(3, field_name),
                               DataOut<2, 3>::type_dof_data,
                               vector_field);
    const Vector<double> area_changes = local_area_changes(x);
    data_out.add_data_vector(area_changes,
                             "area_change",
                             DataOut<2, 3>::type_cell_data);
    data_out.build_patches(mapping,
                           std::max(2u, parameters.degree),
                           DataOut<2, 3>::curved_inner_cells);
    data_out.set_flags(fast_vtk_flags());
    rbc_ifem::write_vtu(data_out, directory + "/" + name + ".vtu", field_data);
  }

  void
  Membrane::build_surface(const Vector<double> &x,
                          Triangulation<2, 3>  &surface) const
  {
    surface.clear();
    surface.copy_triangulation(dof_handler.get_triangulation());
    surface.reset_all_manifolds();
    surface.set_all_manifold_ids(numbers::flat_manifold_id);
    // The copy has the same cells in the same order; the DoFs of component
    // d at a vertex are the d-th vertex DoFs of the FESystem.
    auto surface_cell = surface.begin_active();
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            surface_cell->vertex(v)[d] = x[cell->vertex_dof_index(v, d)];
        ++surface_cell;
      }
  }
} // namespace rbc_ifem

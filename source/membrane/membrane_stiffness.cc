#include <rbc_ifem/membrane/membrane.h>

#include "membrane_internals.h"

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>

#include <Sacado.hpp>

#include <algorithm>
#include <variant>

namespace rbc_ifem
{
  using namespace MembraneInternals;

  namespace
  {
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
   * The first derivatives by the DoFs that the stiffness chains through
   * the sums: of A and V (the penalties' rank-one parts), and per cell of
   * each of its nodes' sums (y, m, w).
   */
  struct Membrane::SumGradients
  {
    /// ∂A/∂x and ∂V/∂x, summed over the ranks.
    Vector<double> area, volume;
    /// Per cell, the 7 (n_a) × (cell DoFs) derivatives of its terms of the
    /// sums (y, m, w) of each local node a (rows 7a to 7a + 6): only of
    /// the cells this rank needs (cells_for_sum_gradients()).
    std::vector<FullMatrix<double>> nodal_sums;
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

  void
  MembraneStiffness::add_diagonal(Vector<double> &diagonal) const
  {
    Vector<double> sparse(diagonal.size());
    for (unsigned int i = 0; i < sparse.size(); ++i)
      sparse[i] = local.diag_element(i);
    if (n_ranks(communicator) > 1)
      add_up_over_ranks(make_array_view(sparse), communicator);
    diagonal += sparse;
    for (const auto &[c, gradient] : rank_one)
      for (unsigned int i = 0; i < diagonal.size(); ++i)
        diagonal[i] += c * gradient[i] * gradient[i];
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
    const ReferenceMetric                 &G     = reference_metric();
    const SurfacePoint<Number>             point = surface_point(tangent,
                                                     G.inverse[c][q],
                                                     G.jacobian[c][q],
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

  void
  Membrane::find_cells_around_nodes()
  {
    numbering->cells_around_node.resize(numbering->n_nodes);
    for (unsigned int c = 0; c < numbering->cell_nodes.size(); ++c)
      for (unsigned int a = 0; a < scalar_fe.n_dofs_per_cell(); ++a)
        numbering->cells_around_node[numbering->cell_nodes[c][a]].emplace_back(
          c, a);
  }

  const SparsityPattern &
  Membrane::stiffness_pattern() const
  {
    // The stiffness couples the DoFs of all cells around a node: the
    // bending energy of a node depends on them through its sums. Made on
    // the first stiffness() of any membrane that shares the numbering, so
    // that a rank that owns no cell never stores it, and one that owns
    // several stores it once.
    if (numbering->stiffness_sparsity.empty())
      {
        DynamicSparsityPattern coupled(dof_handler.n_dofs());
        for (unsigned int i = 0; i < numbering->n_nodes; ++i)
          {
            const std::vector<types::global_dof_index> patch = patch_dofs(i);
            for (const types::global_dof_index row : patch)
              coupled.add_entries(row, patch.begin(), patch.end(), true);
          }
        numbering->stiffness_sparsity.copy_from(coupled);
      }
    return numbering->stiffness_sparsity;
  }

  std::vector<types::global_dof_index>
  Membrane::patch_dofs(const unsigned int i) const
  {
    std::vector<types::global_dof_index> patch;
    for (const auto &[c, a] : numbering->cells_around_node[i])
      patch.insert(patch.end(),
                   numbering->cell_dofs[c].begin(),
                   numbering->cell_dofs[c].end());
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
    K.local.reinit(stiffness_pattern());
    K.rank_one.clear();
    K.communicator = communicator;

    // Every integrand depends on the DoFs only through the point's position
    // and tangents z = L_q x (9 numbers), so derivatives in the cell's DoFs
    // are taken in z, by forward mode per point, and chained with L_q: far
    // cheaper than forward mode over the cell.
    const SumGradients gradients = sum_gradients(x);
    add_cell_hessians(x, d, K.local);
    add_bending_curvature(sums, gradients.nodal_sums, K.local);

    if (parameters.area_penalty > 0.)
      K.rank_one.emplace_back(parameters.area_penalty / area0, gradients.area);
    if (parameters.volume_penalty > 0.)
      K.rank_one.emplace_back(parameters.volume_penalty / volume0,
                              gradients.volume);
  }

  std::vector<bool>
  Membrane::cells_for_sum_gradients() const
  {
    const auto [first_cell, end_cell] = share(numbering->cell_dofs.size());
    const auto [first_node, end_node] = share(numbering->n_nodes);
    std::vector<bool> needed(numbering->cell_dofs.size(), false);
    std::fill(needed.begin() + first_cell, needed.begin() + end_cell, true);
    for (unsigned int i = first_node; i < end_node; ++i)
      for (const auto &[c, a] : numbering->cells_around_node[i])
        needed[c] = true;
    return needed;
  }

  Membrane::SumGradients
  Membrane::sum_gradients(const Vector<double> &x) const
  {
    using First                       = Sacado::Fad::SFad<double, 9>;
    const unsigned int n              = fe.n_dofs_per_cell();
    const auto [first_cell, end_cell] = share(numbering->cell_dofs.size());
    const std::vector<bool> needed    = cells_for_sum_gradients();
    SumGradients            gradients;
    gradients.area.reinit(dof_handler.n_dofs());
    gradients.volume.reinit(dof_handler.n_dofs());
    gradients.nodal_sums.resize(numbering->cell_dofs.size());
    FullMatrix<double> D(n_point_integrands, 9), DL(n_point_integrands, n);
    Vector<double>     values(n), z(9);
    for (unsigned int c = 0; c < numbering->cell_dofs.size(); ++c)
      {
        if (!needed[c])
          continue;
        const bool own = c >= first_cell && c < end_cell;
        x.extract_subvector_to(numbering->cell_dofs[c].begin(),
                               numbering->cell_dofs[c].end(),
                               values.begin());
        FullMatrix<double> &J = gradients.nodal_sums[c];
        J.reinit(7 * scalar_fe.n_dofs_per_cell(), n);
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
            if (own)
              for (unsigned int k = 0; k < n; ++k)
                {
                  gradients.area[numbering->cell_dofs[c][k]] += DL(0, k);
                  gradients.volume[numbering->cell_dofs[c][k]] += DL(1, k);
                }
            add_nodal_sum_derivatives(q, DL, J);
          }
      }
    if (n_ranks(communicator) > 1)
      {
        add_up_over_ranks(make_array_view(gradients.area), communicator);
        add_up_over_ranks(make_array_view(gradients.volume), communicator);
      }
    return gradients;
  }

  void
  Membrane::add_nodal_sum_derivatives(const unsigned int        q,
                                      const FullMatrix<double> &DL,
                                      FullMatrix<double>       &J) const
  {
    for (unsigned int k = 0; k < DL.n(); ++k)
      for (unsigned int a = 0; a < scalar_fe.n_dofs_per_cell(); ++a)
        {
          const double N = shape_values(a, q);
          J(7 * a + 3, k) += N * DL(0, k);
          for (unsigned int e = 0; e < 3; ++e)
            {
              J(7 * a + 4 + e, k) += N * DL(2 + e, k);
              for (unsigned int alpha = 0; alpha < 2; ++alpha)
                J(7 * a + e, k) +=
                  shape_gradients(a, q)[alpha] * DL(5 + 3 * alpha + e, k);
            }
        }
  }

  void
  Membrane::add_cell_hessians(const Vector<double> &x,
                              const Multipliers    &d,
                              SparseMatrix<double> &K) const
  {
    const unsigned int n              = fe.n_dofs_per_cell();
    const auto [first_cell, end_cell] = share(numbering->cell_dofs.size());
    // The law is chosen once, outside the loop over the cells.
    const auto add_with_law = [&](const auto &law) {
      using First  = Sacado::Fad::SFad<double, 9>;
      using Second = Sacado::Fad::SFad<First, 9>;
      FullMatrix<double> cell_matrix(n, n), H(9, 9), HL(9, n);
      Vector<double>     values(n), z(9);
      for (unsigned int c = first_cell; c < end_cell; ++c)
        {
          x.extract_subvector_to(numbering->cell_dofs[c].begin(),
                                 numbering->cell_dofs[c].end(),
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
          K.add(numbering->cell_dofs[c], cell_matrix);
        }
    };
    std::visit(add_with_law, elastic_law);
  }

  void
  Membrane::add_bending_curvature(
    const Sums                            &sums,
    const std::vector<FullMatrix<double>> &nodal_sum_gradients,
    SparseMatrix<double>                  &K) const
  {
    const auto [first_node, end_node] = share(numbering->n_nodes);
    for (unsigned int i = first_node; i < end_node; ++i)
      {
        const std::vector<types::global_dof_index> patch = patch_dofs(i);
        FullMatrix<double> J(7, patch.size()), BJ(7, patch.size()),
          patch_matrix(patch.size(), patch.size());
        for (const auto &[c, a] : numbering->cells_around_node[i])
          for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
            {
              const unsigned int column =
                std::lower_bound(patch.begin(),
                                 patch.end(),
                                 numbering->cell_dofs[c][k]) -
                patch.begin();
              for (unsigned int r = 0; r < 7; ++r)
                J(r, column) += nodal_sum_gradients[c](7 * a + r, k);
            }
        nodal_bending_hessian(sums.laplacian[i],
                              sums.mass[i],
                              sums.normal[i],
                              parameters.bending_modulus,
                              parameters.spontaneous_curvature)
          .mmult(BJ, J);
        J.Tmmult(patch_matrix, BJ);
        K.add(patch, patch_matrix);
      }
  }
} // namespace rbc_ifem

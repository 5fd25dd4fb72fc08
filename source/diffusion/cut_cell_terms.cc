#include <rbc_ifem/diffusion/cut_cell_terms.h>

#include <cmath>

namespace rbc_ifem
{
  namespace
  {
    /**
     * matrix += X Yᵀ: each term below is a sum over quadrature points of
     * products of per-shape numbers, so it is one product of an n × (numbers
     * per point × points) table with another, rows contiguous; with X = Y
     * only the upper half is summed. Four partial sums keep the multiply-
     * adds independent. It replaced a triple loop over points and shape
     * pairs through FEValues' accessors (and beats the reference BLAS's
     * gemm at these sizes, 27 × 81).
     */
    void
    add_product(const FullMatrix<double> &X,
                const FullMatrix<double> &Y,
                FullMatrix<double>       &matrix)
    {
      const unsigned int n = X.m(), length = X.n();
      if (length == 0)
        return;
      const bool symmetric = &X == &Y;
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = symmetric ? i : 0; j < n; ++j)
          {
            const double *x = &X(i, 0), *y = &Y(j, 0);
            double        sum[4] = {0., 0., 0., 0.};
            unsigned int  c      = 0;
            for (; c + 4 <= length; c += 4)
              for (unsigned int l = 0; l < 4; ++l)
                sum[l] += x[c + l] * y[c + l];
            for (; c < length; ++c)
              sum[0] += x[c] * y[c];
            const double total = (sum[0] + sum[1]) + (sum[2] + sum[3]);
            matrix(i, j) += total;
            if (symmetric && j != i)
              matrix(j, i) += total;
          }
    }
  } // namespace

  void
  add_plasma_diffusion(const FEValues<3>   &plasma,
                       const double         permeability,
                       const CutCellShapes &shapes,
                       FullMatrix<double>  &matrix)
  {
    // B(i, 3q + d) = √(αD JxW) ∂_d φ_i(x_q) on the plasma's shapes: B Bᵀ.
    const unsigned int n = shapes.side.size();
    FullMatrix<double> B(n, 3 * plasma.n_quadrature_points);
    for (const unsigned int q : plasma.quadrature_point_indices())
      {
        const double w = std::sqrt(permeability * plasma.JxW(q));
        for (unsigned int i = 0; i < n; ++i)
          if (shapes.side[i] == 0)
            for (unsigned int d = 0; d < 3; ++d)
              B(i, 3 * q + d) = w * plasma.shape_grad(i, q)[d];
      }
    add_product(B, B, matrix);
  }

  void
  add_cytoplasm_reaction(const FEValues<3>   &cytoplasm,
                         const double         permeability,
                         const double         rate,
                         const CutCellShapes &shapes,
                         FullMatrix<double>  &matrix)
  {
    // B(i, 4q + d) = √(α_cD_c JxW) ∂_d φ_i, B(i, 4q + 3) = √(k JxW) φ_i.
    const unsigned int n = shapes.side.size();
    FullMatrix<double> B(n, 4 * cytoplasm.n_quadrature_points);
    for (const unsigned int q : cytoplasm.quadrature_point_indices())
      {
        const double w_grad  = std::sqrt(permeability * cytoplasm.JxW(q));
        const double w_value = std::sqrt(rate * cytoplasm.JxW(q));
        for (unsigned int i = 0; i < n; ++i)
          if (shapes.side[i] == 1)
            {
              for (unsigned int d = 0; d < 3; ++d)
                B(i, 4 * q + d) = w_grad * cytoplasm.shape_grad(i, q)[d];
              B(i, 4 * q + 3) = w_value * cytoplasm.shape_value(i, q);
            }
      }
    add_product(B, B, matrix);
  }

  void
  add_membrane_coupling(const NonMatching::FEImmersedSurfaceValues<3> &membrane,
                        const MembraneCoupling                        &coupling,
                        const CutCellShapes                           &shapes,
                        FullMatrix<double>                            &matrix)
  {
    // With F(i, q) = √JxW {αD ∂ₙφ_i} and J(i, q) = √JxW [φ_i], the terms
    // are (β J − F) Jᵀ − J Fᵀ.
    const unsigned int n        = shapes.side.size();
    const unsigned int n_q      = membrane.n_quadrature_points;
    const double flux_weight[2] = {coupling.plasma_flux, coupling.cell_flux};
    FullMatrix<double> F(n, n_q), J(n, n_q);
    for (const unsigned int q : membrane.quadrature_point_indices())
      {
        const double        w      = std::sqrt(membrane.JxW(q));
        const Tensor<1, 3> &normal = membrane.normal_vector(q);
        for (unsigned int i = 0; i < n; ++i)
          if (shapes.side[i] >= 0)
            {
              F(i, q) = w * flux_weight[shapes.side[i]] *
                        (normal * membrane.shape_grad(i, q));
              J(i, q) = w * shapes.jump_sign[i] * membrane.shape_value(i, q);
            }
      }
    FullMatrix<double> penalised_minus_flux(n, n_q);
    penalised_minus_flux.add(coupling.penalty, J, -1., F);
    add_product(penalised_minus_flux, J, matrix);
    F *= -1.;
    add_product(J, F, matrix);
  }

  void
  add_ghost_penalty(const FEInterfaceValues<3> &face,
                    const unsigned int          field,
                    const double                weight,
                    const double                h,
                    const unsigned int          degree,
                    FullMatrix<double>         &matrix)
  {
    // B(i, 2q) = √w₁ [∂ₙφ_i], B(i, 2q + 1) = √w₂ [∂ₙₙφ_i]: B Bᵀ.
    const unsigned int n     = face.n_current_interface_dofs();
    const auto         jumps = face[FEValuesExtractors::Scalar(field)];
    FullMatrix<double> B(n, 2 * face.n_quadrature_points);
    for (const unsigned int q : face.quadrature_point_indices())
      {
        const Tensor<1, 3> &normal = face.normal(q);
        const double        w1     = std::sqrt(weight * h * face.JxW(q));
        const double        w2 = std::sqrt(weight * h * h * h * face.JxW(q));
        for (unsigned int i = 0; i < n; ++i)
          {
            B(i, 2 * q) = w1 * (normal * jumps.jump_in_gradients(i, q));
            if (degree > 1)
              B(i, 2 * q + 1) =
                w2 * (normal * (jumps.jump_in_hessians(i, q) * normal));
          }
      }
    add_product(B, B, matrix);
  }
} // namespace rbc_ifem

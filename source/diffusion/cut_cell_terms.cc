#include <rbc_ifem/diffusion/cut_cell_terms.h>

namespace rbc_ifem
{
  void
  add_plasma_diffusion(const FEValues<3>   &plasma,
                       const double         permeability,
                       const CutCellShapes &shapes,
                       FullMatrix<double>  &matrix)
  {
    const unsigned int n = shapes.side.size();
    for (const unsigned int q : plasma.quadrature_point_indices())
      for (unsigned int i = 0; i < n; ++i)
        if (shapes.side[i] == 0)
          for (unsigned int j = 0; j < n; ++j)
            if (shapes.side[j] == 0)
              matrix(i, j) += permeability * plasma.shape_grad(i, q) *
                              plasma.shape_grad(j, q) * plasma.JxW(q);
  }

  void
  add_cytoplasm_reaction(const FEValues<3>   &cytoplasm,
                         const double         permeability,
                         const double         rate,
                         const CutCellShapes &shapes,
                         FullMatrix<double>  &matrix)
  {
    const unsigned int n = shapes.side.size();
    for (const unsigned int q : cytoplasm.quadrature_point_indices())
      for (unsigned int i = 0; i < n; ++i)
        if (shapes.side[i] == 1)
          for (unsigned int j = 0; j < n; ++j)
            if (shapes.side[j] == 1)
              matrix(i, j) += (permeability * cytoplasm.shape_grad(i, q) *
                                 cytoplasm.shape_grad(j, q) +
                               rate * cytoplasm.shape_value(i, q) *
                                 cytoplasm.shape_value(j, q)) *
                              cytoplasm.JxW(q);
  }

  void
  add_membrane_coupling(const NonMatching::FEImmersedSurfaceValues<3> &membrane,
                        const MembraneCoupling                        &coupling,
                        const CutCellShapes                           &shapes,
                        FullMatrix<double>                            &matrix)
  {
    const unsigned int n        = shapes.side.size();
    const double flux_weight[2] = {coupling.plasma_flux, coupling.cell_flux};
    std::vector<double> flux(n), jump(n);
    for (const unsigned int q : membrane.quadrature_point_indices())
      {
        // {αD ∂ₙφ_i} and [φ_i], once per shape function.
        const Tensor<1, 3> &normal = membrane.normal_vector(q);
        for (unsigned int i = 0; i < n; ++i)
          if (shapes.side[i] >= 0)
            {
              flux[i] = flux_weight[shapes.side[i]] *
                        (normal * membrane.shape_grad(i, q));
              jump[i] = shapes.jump_sign[i] * membrane.shape_value(i, q);
            }
          else
            flux[i] = jump[i] = 0.;
        const double JxW = membrane.JxW(q);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            matrix(i, j) += (-flux[i] * jump[j] - flux[j] * jump[i] +
                             coupling.penalty * jump[i] * jump[j]) *
                            JxW;
      }
  }

  void
  add_ghost_penalty(const FEInterfaceValues<3> &face,
                    const unsigned int          field,
                    const double                weight,
                    const double                h,
                    const unsigned int          degree,
                    FullMatrix<double>         &matrix)
  {
    const unsigned int  n     = face.n_current_interface_dofs();
    const auto          jumps = face[FEValuesExtractors::Scalar(field)];
    std::vector<double> first(n), second(n);
    for (const unsigned int q : face.quadrature_point_indices())
      {
        // The jumps of ∂ₙφ_i and ∂ₙₙφ_i, once per shape function.
        const Tensor<1, 3> &normal = face.normal(q);
        for (unsigned int i = 0; i < n; ++i)
          {
            first[i]  = normal * jumps.jump_in_gradients(i, q);
            second[i] = degree > 1 ?
                          normal * (jumps.jump_in_hessians(i, q) * normal) :
                          0.;
          }
        const double w1 = weight * h * face.JxW(q);
        const double w2 = weight * h * h * h * face.JxW(q);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            matrix(i, j) +=
              w1 * first[i] * first[j] + w2 * second[i] * second[j];
      }
  }
} // namespace rbc_ifem

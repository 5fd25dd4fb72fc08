#include <rbc_ifem/fluid/velocity_operator.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/matrix_free/tools.h>

namespace rbc_ifem
{
  VelocityOperator::VelocityOperator(
    std::shared_ptr<const MatrixFree<3, double>> matrix_free,
    const unsigned int                           dof_index)
    : matrix_free(std::move(matrix_free))
    , dof_index(dof_index)
  {}

  void
  VelocityOperator::set_coefficients(const double mass_factor,
                                     const double viscosity)
  {
    Evaluator          phi(*matrix_free, dof_index);
    const unsigned int n_q = phi.n_q_points;
    coefficients.resize(matrix_free->n_cell_batches() * n_q);
    for (unsigned int cell = 0; cell < matrix_free->n_cell_batches(); ++cell)
      {
        phi.reinit(cell);
        for (const unsigned int q : phi.quadrature_point_indices())
          {
            // J⁻ᵀ maps reference gradients to real ones: the form
            // μ ∫ ∇u·∇w becomes μ JxW ĝ_uᵀ (J⁻¹J⁻ᵀ) ĝ_w per point.
            const Tensor<2, 3, VectorizedArray<double>> inverse_jacobian =
              phi.inverse_jacobian(q);
            const VectorizedArray<double>               JxW = phi.JxW(q);
            const Tensor<2, 3, VectorizedArray<double>> metric =
              (viscosity * JxW) * transpose(inverse_jacobian) *
              inverse_jacobian;
            coefficients[cell * n_q + q] = {metric[0][0],
                                            metric[0][1],
                                            metric[0][2],
                                            metric[1][1],
                                            metric[1][2],
                                            metric[2][2],
                                            mass_factor * JxW};
          }
      }
    initialize_dof_vector(a_diagonal);
    MatrixFreeTools::compute_diagonal(*matrix_free,
                                      a_diagonal,
                                      &VelocityOperator::apply_on_cell,
                                      this,
                                      dof_index);
  }

  void
  VelocityOperator::apply_on_cell(Evaluator &phi) const
  {
    phi.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
    // The fields at the quadrature points, in reference coordinates:
    // values [component][point], gradients [component][direction][point].
    constexpr unsigned int   n_q       = Evaluator::static_n_q_points;
    VectorizedArray<double> *values    = phi.begin_values();
    VectorizedArray<double> *gradients = phi.begin_gradients();
    const auto *k = &coefficients[phi.get_current_cell_index() * n_q];
    for (unsigned int q = 0; q < n_q; ++q)
      for (unsigned int c = 0; c < 3; ++c)
        {
          values[c * n_q + q] *= k[q][6];
          VectorizedArray<double>      *g  = gradients + 3 * c * n_q + q;
          const VectorizedArray<double> g0 = g[0], g1 = g[n_q], g2 = g[2 * n_q];
          g[0]       = k[q][0] * g0 + k[q][1] * g1 + k[q][2] * g2;
          g[n_q]     = k[q][1] * g0 + k[q][3] * g1 + k[q][4] * g2;
          g[2 * n_q] = k[q][2] * g0 + k[q][4] * g1 + k[q][5] * g2;
        }
    phi.integrate(EvaluationFlags::values | EvaluationFlags::gradients);
  }

  void
  VelocityOperator::apply_on_cells(
    const MatrixFree<3, double>                 &data,
    VelocityVector                              &dst,
    const VelocityVector                        &src,
    const std::pair<unsigned int, unsigned int> &cells) const
  {
    Evaluator phi(data, dof_index);
    for (unsigned int cell = cells.first; cell < cells.second; ++cell)
      {
        phi.reinit(cell);
        phi.read_dof_values(src);
        apply_on_cell(phi);
        phi.distribute_local_to_global(dst);
      }
  }

  void
  VelocityOperator::vmult(VelocityVector &dst, const VelocityVector &src) const
  {
    matrix_free->cell_loop(
      &VelocityOperator::apply_on_cells, this, dst, src, /*zero_dst=*/true);
    if (added_term)
      {
        // The term condenses its constrained rows to zero, so that they
        // stay the identity's.
        const bool ghosted = src.has_ghost_elements();
        if (!ghosted)
          src.update_ghost_values();
        added_product = 0.;
        added_term(src, added_product);
        if (!ghosted)
          src.zero_out_ghost_values();
        dst += added_product;
      }
    for (const unsigned int i : matrix_free->get_constrained_dofs(dof_index))
      dst.local_element(i) = src.local_element(i);
  }

  void
  VelocityOperator::set_added_term(const AddedTerm      &apply,
                                   const VelocityVector &diagonal)
  {
    added_term = apply;
    if (added_term)
      {
        added_diagonal = diagonal;
        initialize_dof_vector(added_product);
      }
  }

  void
  VelocityOperator::Tvmult(VelocityVector &dst, const VelocityVector &src) const
  {
    vmult(dst, src);
  }

  void
  VelocityOperator::initialize_dof_vector(VelocityVector &v) const
  {
    matrix_free->initialize_dof_vector(v, dof_index);
  }

  types::global_dof_index
  VelocityOperator::m() const
  {
    return matrix_free->get_dof_handler(dof_index).n_dofs();
  }

  double
  VelocityOperator::el(const unsigned int, const unsigned int) const
  {
    Assert(false, ExcNotImplemented());
    return 0.;
  }

  std::shared_ptr<DiagonalMatrix<VelocityVector>>
  VelocityOperator::inverse_diagonal() const
  {
    auto inverse = std::make_shared<DiagonalMatrix<VelocityVector>>();
    VelocityVector &diagonal = inverse->get_vector();
    diagonal                 = a_diagonal;
    if (added_term)
      diagonal += added_diagonal;
    for (const unsigned int i : matrix_free->get_constrained_dofs(dof_index))
      diagonal.local_element(i) = 1.;
    for (double &d : diagonal)
      d = 1. / d;
    return inverse;
  }

  void
  VelocityOperator::assemble_matrix(
    const AffineConstraints<double> &constraints,
    TrilinosWrappers::SparseMatrix  &matrix) const
  {
    const DoFHandler<3> &dof_handler = matrix_free->get_dof_handler(dof_index);
    const MPI_Comm       communicator =
      dof_handler.get_triangulation().get_communicator();
    TrilinosWrappers::SparsityPattern sparsity(
      dof_handler.locally_owned_dofs(),
      dof_handler.locally_owned_dofs(),
      DoFTools::extract_locally_relevant_dofs(dof_handler),
      communicator);
    DoFTools::make_sparsity_pattern(dof_handler,
                                    sparsity,
                                    constraints,
                                    /*keep_constrained_dofs=*/false,
                                    Utilities::MPI::this_mpi_process(
                                      communicator));
    sparsity.compress();
    matrix.reinit(sparsity);
    MatrixFreeTools::compute_matrix(*matrix_free,
                                    constraints,
                                    matrix,
                                    &VelocityOperator::apply_on_cell,
                                    this,
                                    dof_index);
  }
} // namespace rbc_ifem

#ifndef rbc_ifem_fluid_velocity_operator_h
#define rbc_ifem_fluid_velocity_operator_h

#include <rbc_ifem/fluid/fluid_vectors.h>

#include <deal.II/base/subscriptor.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <functional>
#include <memory>

namespace rbc_ifem
{
  /**
   * The velocity block of the plasma's Stokes operator,
   *
   *   A = (ρ/Δt) M + μ K,   (A v, w) = (ρ/Δt)(v, w) + μ(∇v, ∇w),
   *
   * on the vector Q2 space, applied matrix-free (deal.II's MatrixFree and
   * FEEvaluation: sum factorisation at the quadrature points, no matrix
   * stored). The gradient form of the viscous term couples no two
   * components. On the DoFs its constraints fix (boundary values, hanging
   * nodes, periodic images) it is the identity, so that it is invertible
   * on the whole vector and the multigrid smoother's eigenvalue estimate
   * sees no zero eigenvalue.
   *
   * The cell kernel works on the reference cell: at each quadrature point
   * it multiplies the reference gradients by the metric μ JxW J⁻¹J⁻ᵀ and
   * the values by (ρ/Δt) JxW, both stored (set_coefficients()). That is
   * 27 multiply-adds per point instead of the 63 of transforming the
   * gradients to the real cell and back, which is most of the operator's
   * time on the curved (non-affine) cells of the capillary.
   *
   * VelocityMultigrid uses one per level; on the finest it shares the
   * MatrixFree of the StokesOperator.
   */
  class VelocityOperator : public Subscriptor
  {
  public:
    using value_type = double;
    /// The cell evaluator: Q2, three quadrature points per direction, three
    /// components.
    using Evaluator = FEEvaluation<3, 2, 3, 3, double>;

    /// On the DoFs @p dof_index of @p matrix_free, which it shares.
    VelocityOperator(std::shared_ptr<const MatrixFree<3, double>> matrix_free,
                     const unsigned int                           dof_index);

    /// The coefficients ρ/Δt [pN s/µm⁴] and μ [pN s/µm²]; stores the
    /// kernel's coefficients at every quadrature point.
    void
    set_coefficients(const double mass_factor, const double viscosity);

    void
    vmult(VelocityVector &dst, const VelocityVector &src) const;
    /// A is symmetric.
    void
    Tvmult(VelocityVector &dst, const VelocityVector &src) const;

    /// @p v with this operator's layout (owned entries and ghosts).
    void
    initialize_dof_vector(VelocityVector &v) const;

    types::global_dof_index
    m() const;

    /// Not available matrix-free; needed only to compile deal.II's
    /// Chebyshev smoother, which takes the diagonal from inverse_diagonal().
    double
    el(const unsigned int, const unsigned int) const;

    /// The inverse of A's diagonal (1 on the constrained DoFs).
    std::shared_ptr<DiagonalMatrix<VelocityVector>>
    inverse_diagonal() const;

    /**
     * A assembled into @p matrix, with @p constraints (the ones of its
     * MatrixFree; their rows get a unit diagonal): for the algebraic
     * multigrid on the coarsest level.
     */
    void
    assemble_matrix(const AffineConstraints<double> &constraints,
                    TrilinosWrappers::SparseMatrix  &matrix) const;

    /// The cell integral of A on @p phi, whose DoF values are set.
    void
    apply_on_cell(Evaluator &phi) const;

    /// A term added to A: @p apply adds it times its first argument (ghosted)
    /// to its second; @p diagonal is (an estimate of) its diagonal, which
    /// inverse_diagonal() includes. An empty @p apply removes it.
    using AddedTerm =
      std::function<void(const VelocityVector &, VelocityVector &)>;
    void
    set_added_term(const AddedTerm &apply, const VelocityVector &diagonal);

  private:
    void
    apply_on_cells(const MatrixFree<3, double>                 &matrix_free,
                   VelocityVector                              &dst,
                   const VelocityVector                        &src,
                   const std::pair<unsigned int, unsigned int> &cells) const;

    std::shared_ptr<const MatrixFree<3, double>> matrix_free;
    const unsigned int                           dof_index;
    /// Per cell batch and quadrature point (cell-major): the upper
    /// triangle of the metric μ JxW J⁻¹J⁻ᵀ (xx, xy, xz, yy, yz, zz), then
    /// the mass weight (ρ/Δt) JxW.
    AlignedVector<std::array<VectorizedArray<double>, 7>> coefficients;
    /// The diagonal of A, at the coefficients of set_coefficients().
    VelocityVector         a_diagonal;
    AddedTerm              added_term;
    VelocityVector         added_diagonal;
    mutable VelocityVector added_product;
  };
} // namespace rbc_ifem

#endif

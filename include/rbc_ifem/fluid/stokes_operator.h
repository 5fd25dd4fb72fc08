#ifndef rbc_ifem_fluid_stokes_operator_h
#define rbc_ifem_fluid_stokes_operator_h

#include <rbc_ifem/fluid/fluid_vectors.h>

#include <deal.II/base/table.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * The plasma's discrete operators in Taylor-Hood Q2-Q1, matrix-free: one
   * deal.II MatrixFree holds the velocity (DoF index 0, FESystem of three
   * FE_Q(2)) and the pressure (DoF index 1, FE_Q(1)) with their homogeneous
   * constraints, and every operator is a loop over its cells that evaluates
   * the fields at the 3×3×3 Gauss points by sum factorisation. Nothing is
   * assembled, so the operators cost no setup and little memory, and a
   * change of Δt or of the linearisation point costs nothing.
   *
   * The backward-Euler step's residual, with the continuity equation
   * scaled by μ (FluidProblem):
   *
   *   R_v(w) = (ρ/Δt)(v - vⁿ, w) [+ ρ((∇v)v, w)] + μ(∇v, ∇w) - (p, ∇·w)
   *   R_p(q) = -μ(∇·v, q)
   *
   * and its Jacobian J (vmult()): the Stokes operator, or with convection
   * the Newton linearisation about a given state. Rows of constrained DoFs
   * are zero in the residual and the identity in J.
   */
  class StokesOperator
  {
  public:
    using VelocityEvaluator = FEEvaluation<3, 2, 3, 3, double>;
    using PressureEvaluator = FEEvaluation<3, 1, 3, 1, double>;

    /// The DoF index of the velocity and the pressure in the MatrixFree.
    static constexpr unsigned int velocity_index = 0, pressure_index = 1;

    /// Set up the MatrixFree; the arguments must outlive this object.
    StokesOperator(const Mapping<3>                &mapping,
                   const DoFHandler<3>             &velocity_dof_handler,
                   const DoFHandler<3>             &pressure_dof_handler,
                   const AffineConstraints<double> &velocity_constraints,
                   const AffineConstraints<double> &pressure_constraints);

    /// The density ρ, viscosity μ and time step Δt of the operators.
    void
    set_coefficients(const double density,
                     const double viscosity,
                     const double time_step);

    /**
     * Linearise the convective term about @p state (ghosted), for the
     * Newton steps of Navier-Stokes: v and ∇v are stored at every
     * quadrature point. Without a call, or after clear_convection(), J is
     * the Stokes operator.
     */
    void
    set_convection(const FluidVector &state);
    void
    clear_convection();

    /// @p v with the layout of the operators' vectors, (v, p) blocks.
    void
    initialize_dof_vector(FluidVector &v) const;

    /// dst = J src.
    void
    vmult(FluidVector &dst, const FluidVector &src) const;

    /**
     * dst = R(state) for the velocity @p old_velocity of the last step,
     * without the loads (FluidProblem subtracts them). @p state and
     * @p old_velocity are ghosted and hold their boundary values and
     * hanging-node values (they are read as they are, unconstrained).
     * @p convection adds ρ(∇v)v.
     */
    void
    residual(FluidVector          &dst,
             const FluidVector    &state,
             const VelocityVector &old_velocity,
             const bool            convection) const;

    /// dst = the pressure's term in the momentum rows, -(p, ∇·w), for p =
    /// @p pressure.
    void
    apply_pressure_gradient(VelocityVector       &dst,
                            const PressureVector &pressure) const;

    /// The inverse diagonal of M_p.
    std::shared_ptr<DiagonalMatrix<PressureVector>>
    inverse_pressure_mass_diagonal() const;

    /// Add ∫ f·w of a constant force density @p f [pN/µm³] to @p load.
    void
    add_uniform_force(const Tensor<1, 3> &f, VelocityVector &load) const;

    std::shared_ptr<const MatrixFree<3, double>>
    get_matrix_free() const;

  private:
    void
    apply_on_cells(const MatrixFree<3, double>                 &data,
                   FluidVector                                 &dst,
                   const FluidVector                           &src,
                   const std::pair<unsigned int, unsigned int> &cells) const;
    void
    pressure_gradient_on_cells(
      const MatrixFree<3, double>                 &data,
      VelocityVector                              &dst,
      const PressureVector                        &pressure,
      const std::pair<unsigned int, unsigned int> &cells) const;
    void
    pressure_mass_on_cell(PressureEvaluator &phi) const;

    std::shared_ptr<MatrixFree<3, double>> matrix_free;
    double density = 0., viscosity = 0., time_step = 1.;
    /// Newton's linearisation point: v and ∇v per cell batch and
    /// quadrature point (empty for Stokes).
    Table<2, Tensor<1, 3, VectorizedArray<double>>> convecting_velocity;
    Table<2, Tensor<2, 3, VectorizedArray<double>>> convecting_gradient;
  };
} // namespace rbc_ifem

#endif

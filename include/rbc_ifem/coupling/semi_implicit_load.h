#ifndef rbc_ifem_coupling_semi_implicit_load_h
#define rbc_ifem_coupling_semi_implicit_load_h

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/immersed_coupling.h>

#include <deal.II/lac/affine_constraints.h>


namespace rbc_ifem
{
  /**
   * The load of the semi-implicit coupling (Immersed cells/Coupling =
   * semi-implicit, doc/ifem.md): the membrane forces at the end of the
   * step, linearised about its start with the cells' tangent stiffness K,
   *
   *   F(xⁿ + δ) ≈ Fⁿ - K δ,   δ = Δt S v,
   *
   * so that the fluid's load is Sᵀ Fⁿ - L v with L v = Δt Sᵀ K S v (S
   * interpolates at the membrane points, Sᵀ spreads). Fⁿ is spread as in
   * the explicit coupling; this object is the L that
   * FluidProblem::set_velocity_load() takes: one interpolation, one
   * product with K (CellPopulation::linearize() at the step's start) and
   * one spreading per FGMRES iteration.
   */
  class SemiImplicitLoad
  {
  public:
    /// L of @p cells, coupled by @p coupling, with the fluid's zero
    /// @p constraints; @p time_step is read at every use.
    SemiImplicitLoad(const ImmersedCoupling          &coupling,
                     const CellPopulation            &cells,
                     const AffineConstraints<double> &constraints,
                     const double                    &time_step);

    /// Add L @p v (ghosted) to @p result (ghost entries zero, compressed
    /// here).
    void
    operator()(const VelocityVector &v, VelocityVector &result) const;

    /// Add an estimate of L's diagonal to @p result (compressed here):
    /// Δt Sᵀ diag(K) S's, which leaves out K's entries between points;
    /// @p stiffness_diagonal is diag(K), CellPopulation::stiffness_diagonal().
    void
    add_diagonal(const std::vector<Tensor<1, 3>> &stiffness_diagonal,
                 VelocityVector                  &result) const;

  private:
    const ImmersedCoupling          &coupling;
    const CellPopulation            &cells;
    const AffineConstraints<double> &constraints;
    const double                    &time_step;
  };
} // namespace rbc_ifem

#endif

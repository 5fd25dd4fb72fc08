#ifndef rbc_ifem_coupling_semi_implicit_load_h
#define rbc_ifem_coupling_semi_implicit_load_h

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/coupling/point_exchange.h>

#include <deal.II/lac/affine_constraints.h>

#include <memory>


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
   *
   * On several ranks nothing of it is summed over the ranks: each rank
   * interpolates at the points in its fluid cells, a PointExchange sends
   * the values to the ranks whose rows of K read them, each owner
   * multiplies its cells' rows, and the exchange sends the products back
   * to the points' fluid ranks to be spread. The exchange is set up again
   * whenever the points were placed or K was taken since (one some-to-some
   * at the first product of a step).
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
    /// @p stiffness_diagonal is diag(K) in this rank's rows,
    /// CellPopulation::owned_stiffness_diagonal().
    void
    add_diagonal(const std::vector<Tensor<1, 3>> &stiffness_diagonal,
                 VelocityVector                  &result) const;

  private:
    /// The exchange for the current placement and stiffness, set up anew
    /// if either changed (collective, every rank alike).
    const PointExchange &
    current_exchange() const;

    const ImmersedCoupling                      &coupling;
    const CellPopulation                        &cells;
    const AffineConstraints<double>             &constraints;
    const double                                &time_step;
    mutable std::shared_ptr<const PointExchange> exchange;
    /// The placement and stiffness the exchange was set up for.
    mutable unsigned int placement_seen = 0, stiffness_seen = 0;
  };
} // namespace rbc_ifem

#endif

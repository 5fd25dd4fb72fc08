#ifndef rbc_ifem_membrane_membrane_equilibrium_h
#define rbc_ifem_membrane_membrane_equilibrium_h

#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/lac/vector.h>

#include <functional>

namespace rbc_ifem
{
  using namespace dealii;

  /// How a static solve ended.
  struct EquilibriumReport
  {
    unsigned int   iterations = 0;
    double         residual   = 0.; ///< largest nodal force imbalance [pN]
    MembraneEnergy energy;
  };

  /**
   * The static equilibrium of a membrane under fixed external nodal forces
   * f (one entry per DoF, [pN]): the minimum of Π(x) = E(x) - f·x, found
   * from @p x (updated in place) by L-BFGS (the last 20 steps) with a
   * backtracking line search on Π. Converged when the largest nodal
   * residual |F(x) + f| is below @p tolerance [pN]; throws SolverFailure
   * after @p max_iterations. Rigid motions cost no energy; with balanced
   * forces they never enter the search directions.
   */
  EquilibriumReport
  find_equilibrium(const Membrane       &membrane,
                   const Vector<double> &external_forces,
                   Vector<double>       &x,
                   const double          tolerance,
                   const unsigned int    max_iterations);

  /**
   * An external potential U(x) of the membrane's positions: returns U and
   * adds its forces -∂U/∂x to the second argument (one entry per DoF).
   */
  using ExternalPotential =
    std::function<double(const Vector<double> &, Vector<double> &)>;

  /**
   * The same for forces that depend on the positions: the minimum of
   * Π(x) = E(x) + U(x). A U that is infinite where x is not allowed (a
   * wall) is respected: such steps are halved.
   */
  EquilibriumReport
  find_equilibrium(const Membrane          &membrane,
                   const ExternalPotential &external,
                   Vector<double>          &x,
                   const double             tolerance,
                   const unsigned int       max_iterations);
} // namespace rbc_ifem

#endif

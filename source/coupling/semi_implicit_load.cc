#include <rbc_ifem/coupling/semi_implicit_load.h>

namespace rbc_ifem
{
  SemiImplicitLoad::SemiImplicitLoad(
    const ImmersedCoupling          &coupling,
    const CellPopulation            &cells,
    const AffineConstraints<double> &constraints,
    const double                    &time_step)
    : coupling(coupling)
    , cells(cells)
    , constraints(constraints)
    , time_step(time_step)
  {}

  void
  SemiImplicitLoad::operator()(const VelocityVector &v,
                               VelocityVector       &result) const
  {
    std::vector<Tensor<1, 3>> displacements = coupling.interpolate(v);
    for (Tensor<1, 3> &d : displacements)
      d *= time_step;
    coupling.spread(cells.stiffness_product(displacements),
                    constraints,
                    result);
  }

  void
  SemiImplicitLoad::add_diagonal(
    const std::vector<Tensor<1, 3>> &stiffness_diagonal,
    VelocityVector                  &result) const
  {
    std::vector<Tensor<1, 3>> diagonal = stiffness_diagonal;
    for (Tensor<1, 3> &d : diagonal)
      d *= time_step;
    coupling.spread_squares(diagonal, constraints, result);
  }
} // namespace rbc_ifem

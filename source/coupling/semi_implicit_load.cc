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

  const PointExchange &
  SemiImplicitLoad::current_exchange() const
  {
    if (!exchange || placement_seen != coupling.n_placements() ||
        stiffness_seen != cells.stiffness_serial())
      {
        const std::vector<unsigned int> &fluid_ranks = coupling.point_ranks();
        exchange =
          std::make_shared<const PointExchange>(coupling.get_communicator(),
                                                fluid_ranks,
                                                cells.point_owners(fluid_ranks),
                                                cells.points_read());
        placement_seen = coupling.n_placements();
        stiffness_seen = cells.stiffness_serial();
      }
    return *exchange;
  }

  void
  SemiImplicitLoad::operator()(const VelocityVector &v,
                               VelocityVector       &result) const
  {
    const PointExchange      &points        = current_exchange();
    std::vector<Tensor<1, 3>> displacements = coupling.evaluate(v);
    points.to_readers(displacements);
    for (Tensor<1, 3> &d : displacements)
      d *= time_step;
    std::vector<Tensor<1, 3>> forces =
      cells.owned_stiffness_product(displacements);
    points.to_fluid_ranks(forces);
    coupling.spread(forces, constraints, result);
  }

  void
  SemiImplicitLoad::add_diagonal(
    const std::vector<Tensor<1, 3>> &stiffness_diagonal,
    VelocityVector                  &result) const
  {
    std::vector<Tensor<1, 3>> diagonal = stiffness_diagonal;
    current_exchange().to_fluid_ranks(diagonal);
    for (Tensor<1, 3> &d : diagonal)
      d *= time_step;
    coupling.spread_squares(diagonal, constraints, result);
  }
} // namespace rbc_ifem

// mpirun: 2 3 4

// The cells' mechanics computed by their owners (CellPopulation on a
// communicator, CellOwners): five Evans-Fung cells at randomly perturbed
// positions, all energy terms on, pressed together in a periodic segment so
// that every cell touches its neighbours (the last the first across the end)
// and the wall, give every rank the energy, the forces, the products with the
// tangent stiffness and its diagonal, and the gaps, of the same population
// computed alone, to round-off (the gaps exactly). The ranks own runs of
// neighbours, so the pairs where two runs meet (and the pair across the end)
// are split between two owners, each seeing the other's cell as a ghost. Then
// the train moves along the segment in steps of half a spacing until cells have
// crossed the end and gone to other ranks: at every step every cell has one
// owner, the owned points add up, and the forces and K v still equal those
// computed alone. Last, squeezed into a narrower capillary by their owners,
// the cells take the shapes squeezed on one rank, bit for bit. The
// semi-implicit load L v = Δt Sᵀ K S v on a fully distributed mesh of the
// segment, its values sent point to point between the points' fluid ranks
// and the owners (SemiImplicitLoad, PointExchange), equals the load summed
// over the ranks with K taken alone, and so does its diagonal. A rank keeps
// the Membranes of its own cells and of the first only, made anew for a cell
// it takes over. Runs on 2,
// 3 and 4 ranks (five cells share out unevenly).

#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/coupling/contact_gaps.h>
#include <rbc_ifem/coupling/semi_implicit_load.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>

#include "check.h"

#include <deal.II/base/function_lib.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "unit/membrane/membrane_fixtures.h"

using namespace rbc_ifem;
using test::every_term;

namespace
{
  constexpr unsigned int n_cells = 5;
  /// Between the cells' centres, a little more than their thickness [µm].
  constexpr double spacing = 3.;
  /// The periodic segment, so that cell 4 meets cell 0 across the end.
  constexpr double period      = n_cells * spacing;
  constexpr double wall_radius = 4.3; ///< a cell's radius is 3.9 µm
  /// A capillary the cells must be squeezed into (squeeze_into_lumen()).
  constexpr double narrow_radius = 3.6;

  std::vector<CellPlacement>
  train()
  {
    std::vector<CellPlacement> cells;
    for (unsigned int c = 0; c < n_cells; ++c)
      cells.push_back(CellPlacement{Point<3>(spacing * (c + 0.5), 0., 0.),
                                    Tensor<1, 3>({1., 0., 0.})});
    return cells;
  }

  /// Repulsion, aggregation (its 2 µm cutoff reaches past the neighbours)
  /// and the wall.
  InteractionParameters
  every_interaction()
  {
    InteractionParameters interactions;
    interactions.repulsion_range = 0.6;
    interactions.aggregation     = true;
    interactions.wall_range      = 0.6;
    return interactions;
  }

  /// @p n random vectors of entries in (-@p amplitude, @p amplitude): the
  /// same on every rank.
  std::vector<Tensor<1, 3>>
  random_points(const unsigned int n,
                const double       amplitude,
                std::mt19937      &random)
  {
    std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
    std::vector<Tensor<1, 3>>              result(n);
    for (Tensor<1, 3> &t : result)
      for (unsigned int d = 0; d < 3; ++d)
        t[d] = uniform(random);
    return result;
  }

  /// |a - b| / |b| over every point.
  double
  relative_difference(const std::vector<Tensor<1, 3>> &a,
                      const std::vector<Tensor<1, 3>> &b)
  {
    double difference = 0., norm = 0.;
    for (unsigned int i = 0; i < b.size(); ++i)
      {
        difference += (a[i] - b[i]).norm_square();
        norm += b[i].norm_square();
      }
    return std::sqrt(difference / norm);
  }

  /// Every cell has one owner and every point is owned once: each rank
  /// counts the cells and points it owns. A rank keeps the Membranes of its
  /// own cells and of the first (the model) only, each made where its cell
  /// was placed: with the reference positions of the population @p alone,
  /// which keeps every cell.
  void
  check_owners(Checker              &check,
               const CellPopulation &cells,
               const CellPopulation &alone)
  {
    bool kept_own = true, own_membranes = true;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        kept_own =
          kept_own && cells.holds(c) == (cells.owners().owns(c) || c == 0);
        if (cells.holds(c))
          own_membranes =
            own_membranes && cells.membranes()[c]->reference_positions() ==
                               alone.membranes()[c]->reference_positions();
      }
    check.holds("a rank keeps the Membranes of its cells and the model's",
                kept_own);
    check.holds("each kept Membrane is made where its cell was placed",
                own_membranes);

    const CellOwners  &owners = cells.owners();
    const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    unsigned int       mine = 0, my_points = 0;
    bool               agrees = true;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        mine += owners.owns(c);
        my_points += owners.owns(c) ? cells.membranes()[c]->nodes().size() : 0;
        agrees = agrees && owners.owns(c) == (owners.owner(c) == rank);
      }
    check.near("cells owned, summed over the ranks",
               Utilities::MPI::sum(mine, MPI_COMM_WORLD),
               n_cells,
               0.);
    check.near("points owned, summed over the ranks",
               Utilities::MPI::sum(my_points, MPI_COMM_WORLD),
               cells.n_points(),
               0.);
    check.holds("owns(c) is owner(c) == this rank on every rank",
                Utilities::MPI::min(static_cast<unsigned int>(agrees),
                                    MPI_COMM_WORLD) == 1);
    check.holds("each rank owns a part of the cells, not all",
                Utilities::MPI::max(mine, MPI_COMM_WORLD) < n_cells);
  }

  /// |a - b| / |b| of two velocity-space vectors.
  double
  relative_difference(const VelocityVector &a, const VelocityVector &b)
  {
    VelocityVector difference = a;
    difference -= b;
    return difference.l2_norm() / b.l2_norm();
  }

  /**
   * The largest difference of the last forces of the cells this rank owns
   * in @p owned from those of @p alone, over the largest force of @p alone.
   */
  double
  owned_rows_difference(const CellPopulation &owned,
                        const CellPopulation &alone)
  {
    double difference = 0., largest = 0.;
    for (unsigned int c = 0; c < alone.size(); ++c)
      {
        largest = std::max(largest, alone.last_forces()[c].linfty_norm());
        if (owned.owners().owns(c))
          {
            Vector<double> d = owned.last_forces()[c];
            d -= alone.last_forces()[c];
            difference = std::max(difference, d.linfty_norm());
          }
      }
    return difference / largest;
  }

  /// Not a number at the first DoF of the last cell, added by its owner.
  class BrokenForce : public CellForce
  {
  public:
    explicit BrokenForce(const CellOwners &owners)
      : owners(owners)
    {}

    CellForceReport
    add_forces(const std::vector<Vector<double>> &,
               std::vector<Vector<double>> &forces) const override
    {
      if (owners.owns(forces.size() - 1))
        forces.back()[0] = std::numeric_limits<double>::quiet_NaN();
      return {};
    }

    std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &) const override
    {
      return nullptr;
    }

  private:
    const CellOwners &owners;
  };

  /**
   * The fluid loads of the @p owned cells, point to point, against the same
   * summed over the ranks from the cells @p alone, on the periodic
   * capillary of the train (refined once, fully distributed in slabs): the
   * forces F (compute_owned_forces(), to the fluid ranks), and L v and L's
   * diagonal estimate (SemiImplicitLoad) for a smooth v.
   */
  void
  check_loads(Checker &check, CellPopulation &owned, CellPopulation &alone)
  {
    GeometryParameters geometry;
    geometry.capillary_radius = wall_radius;
    geometry.capillary_length = period;
    geometry.periodic         = true;
    parallel::fullydistributed::Triangulation<3> mesh(MPI_COMM_WORLD);
    create_distributed_mesh_hierarchy(
      mesh,
      [&](Triangulation<3> &serial) { create_fluid_mesh(serial, geometry, 0); },
      [](Triangulation<3> &serial, const MeshZone &zone) {
        zone.refine_global(serial, 1);
      },
      true);
    const MappingQ<3> mapping(2);
    const FESystem<3> fe(FE_Q<3>(2), 3);
    DoFHandler<3>     dofs(mesh);
    dofs.distribute_dofs(fe);
    const IndexSet relevant = DoFTools::extract_locally_relevant_dofs(dofs);
    const auto     vector   = [&]() {
      return VelocityVector(dofs.locally_owned_dofs(),
                            relevant,
                            MPI_COMM_WORLD);
    };
    VelocityVector v = vector();
    VectorTools::interpolate(mapping, dofs, Functions::CosineFunction<3>(3), v);
    v.update_ghost_values();
    AffineConstraints<double> none;
    none.close();
    ImmersedCoupling coupling(mesh, mapping, dofs, period);
    coupling.place(owned.points());

    const double              dt            = 2e-4;
    std::vector<Tensor<1, 3>> displacements = coupling.interpolate(v);
    for (Tensor<1, 3> &d : displacements)
      d *= dt;
    VelocityVector summed = vector(), exchanged = vector();
    coupling.spread(alone.stiffness_product(displacements), none, summed);
    const SemiImplicitLoad load(coupling, owned, none, dt);
    load(v, exchanged);
    check.at_most("L v, point to point against summed (relative)",
                  relative_difference(exchanged, summed),
                  1e-12);

    std::vector<Tensor<1, 3>> diagonal = alone.stiffness_diagonal();
    for (Tensor<1, 3> &d : diagonal)
      d *= dt;
    summed    = 0.;
    exchanged = 0.;
    coupling.spread_squares(diagonal, none, summed);
    load.add_diagonal(owned.owned_stiffness_diagonal(), exchanged);
    check.at_most("L's diagonal estimate, point to point against summed",
                  relative_difference(exchanged, summed),
                  1e-12);

    // The forces: each owner's rows to the points' fluid ranks.
    const std::vector<unsigned int> &fluid_ranks = coupling.point_ranks();
    std::vector<Tensor<1, 3>>        forces      = owned.compute_owned_forces();
    PointExchange(MPI_COMM_WORLD, fluid_ranks, owned.point_owners(fluid_ranks))
      .to_fluid_ranks(forces);
    summed    = 0.;
    exchanged = 0.;
    coupling.spread(alone.compute_forces(), none, summed);
    coupling.spread(forces, none, exchanged);
    check.at_most("F spread, point to point against summed (relative)",
                  relative_difference(exchanged, summed),
                  1e-12);
    check.at_most("energy with owned forces against alone (relative)",
                  std::abs(owned.energy() - alone.energy()) / alone.energy(),
                  1e-13);
    check.holds("the forces are finite, on every rank", owned.forces_finite());

    // Not a vacuous check: values travel (points whose fluid rank is not
    // their owner, contact partners read across two owners).
    const PointExchange exchange(MPI_COMM_WORLD,
                                 fluid_ranks,
                                 owned.point_owners(fluid_ranks),
                                 owned.points_read());
    check.at_least("points travelling, summed over the ranks",
                   Utilities::MPI::sum(exchange.n_points_travelling(),
                                       MPI_COMM_WORLD),
                   1);
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports
  Checker      check;
  std::mt19937 random(3);

  CellParameters cell_parameters;
  cell_parameters.surface_refinements = 2;
  CellPopulation alone(train(), cell_parameters, every_term());
  CellPopulation owned(
    train(), cell_parameters, every_term(), MPI_COMM_WORLD, period);
  for (CellPopulation *cells : {&alone, &owned})
    add_interaction_forces(*cells, every_interaction(), wall_radius, period);

  // Both at the same perturbed positions: move every point by a random
  // velocity for a unit time.
  const std::vector<Tensor<1, 3>> velocities =
    random_points(alone.n_points(), 0.05, random);
  alone.move(velocities, 1.);
  owned.move(velocities, 1.);

  const std::vector<Tensor<1, 3>> f_alone = alone.compute_forces(),
                                  f_owned = owned.compute_forces();
  check.at_most("energy, by owners against alone (relative)",
                std::abs(owned.energy() - alone.energy()) / alone.energy(),
                1e-13);
  check.at_most("forces, by owners against alone (relative)",
                relative_difference(f_owned, f_alone),
                1e-12);

  const auto gaps = [](const CellPopulation &cells) {
    std::vector<double> result;
    for (const CellGaps &g : measure_gaps(cells.membranes(),
                                          cells.positions(),
                                          wall_radius,
                                          period,
                                          cells.owners()))
      result.insert(result.end(), {g.to_cells, g.to_wall});
    return result;
  };
  const std::vector<double> gaps_alone = gaps(alone);
  check.at_most("largest gap of a cell to another or the wall [µm]",
                *std::max_element(gaps_alone.begin(), gaps_alone.end()),
                0.6);
  check.holds("gaps, by owners, equal those alone", gaps(owned) == gaps_alone);

  alone.linearize();
  owned.linearize();
  const std::vector<Tensor<1, 3>> v =
    random_points(alone.n_points(), 1., random);
  check.at_most("K v, by owners against alone (relative)",
                relative_difference(owned.stiffness_product(v),
                                    alone.stiffness_product(v)),
                1e-12);
  check.at_most("diag(K), by owners against alone (relative)",
                relative_difference(owned.stiffness_diagonal(),
                                    alone.stiffness_diagonal()),
                1e-12);

  check_loads(check, owned, alone);

  check_owners(check, owned, alone);
  check.holds("the ranks own runs of neighbours (cells 3 and 4 together)",
              owned.owners().owner(3) == owned.owners().owner(4));

  // The train moves on by half a spacing at a time, over two spacings: the
  // last cells cross the end and become the first, and change owner.
  const std::vector<Tensor<1, 3>> along(alone.n_points(),
                                        Tensor<1, 3>({spacing / 2., 0., 0.}));
  double forces_moved = 0., forces_handed_over = 0., products_moved = 0.;
  alone.compute_forces();
  owned.compute_owned_forces();
  for (unsigned int step = 0; step < 4; ++step)
    {
      alone.move(along, 1.);
      owned.move(along, 1.);
      check_owners(check, owned, alone);
      // The forces from before the move, each with its cell's new owner.
      forces_handed_over =
        std::max(forces_handed_over, owned_rows_difference(owned, alone));
      alone.compute_forces();
      owned.compute_owned_forces();
      forces_moved =
        std::max(forces_moved, owned_rows_difference(owned, alone));
      alone.linearize();
      owned.linearize();
      products_moved =
        std::max(products_moved,
                 relative_difference(owned.stiffness_product(v),
                                     alone.stiffness_product(v)));
    }
  check.at_least("cells handed to another rank as the train moved",
                 owned.owners().n_handovers(),
                 2);
  check.at_most("forces after each move, by owners against alone",
                forces_moved,
                1e-12);
  check.at_most("forces of the cells handed over, on their new owners",
                forces_handed_over,
                1e-12);
  check.at_most("K v after each move, by owners against alone",
                products_moved,
                1e-12);

  // Squeezed into a narrower capillary by their owners, each cell alone,
  // the cells take the same shapes, bit for bit, as squeezed on one rank.
  const auto squeezed = [](const CellPopulation        &cells,
                           std::vector<Vector<double>> &x) {
    x = cells.positions();
    return WallRepulsion(cells.membranes(),
                         narrow_radius,
                         RepulsivePotential(10., 0.3),
                         cells.owners())
      .squeeze_into_lumen(x);
  };
  std::vector<Vector<double>> x_alone, x_owned;
  const unsigned int          stages_alone = squeezed(alone, x_alone);
  check.at_least("stages of the squeeze, alone", stages_alone, n_cells);
  check.holds("stages by owners as alone",
              squeezed(owned, x_owned) == stages_alone);
  check.holds("squeezed positions by owners equal those alone",
              x_owned == x_alone);

  // A force not a number on the last cell: every rank learns it, not only
  // the cell's owner.
  owned.add_force(std::make_unique<BrokenForce>(owned.owners()));
  owned.compute_owned_forces();
  check.holds("a force not finite, seen by every rank", !owned.forces_finite());
  return check.exit_code();
}

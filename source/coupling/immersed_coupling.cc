#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  namespace
  {
    /// How far outside the reference cell a point may be found: the
    /// round-off of the mapping's inverse at faces and curved edges. A
    /// point exactly on a face between two layers of a 1 mm capillary came
    /// out 1.6e-10 outside both cells (benchmarks/scaling.sh, 200 cells).
    constexpr double inside_tolerance = 1e-8;
    /// How far inside a cell a point must be to be in no other: well above
    /// inside_tolerance.
    constexpr double       clearly_inside = 1e-7;
    constexpr unsigned int nobody = std::numeric_limits<unsigned int>::max();
  } // namespace

  ImmersedCoupling::ImmersedCoupling(const Triangulation<3> &triangulation,
                                     const Mapping<3>       &mapping,
                                     const DoFHandler<3> &velocity_dof_handler,
                                     const std::optional<double> &period)
    : triangulation(triangulation)
    , mapping(mapping)
    , dof_handler(velocity_dof_handler)
    , period(period)
    , cache(triangulation, mapping)
  {
    const FiniteElement<3> &fe = dof_handler.get_fe();
    for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
      velocity_shape_functions.emplace_back(
        k, fe.system_to_component_index(k).first);
  }

  std::optional<Point<3>>
  ImmersedCoupling::reference_in(const CellIterator &cell,
                                 const Point<3>     &p) const
  {
    if (!cell->is_locally_owned())
      return std::nullopt;
    try
      {
        const Point<3> reference = mapping.transform_real_to_unit_cell(cell, p);
        if (GeometryInfo<3>::is_inside_unit_cell(reference, inside_tolerance))
          return reference;
      }
    catch (const Mapping<3>::ExcTransformationFailed &)
      {
        // far outside this cell
      }
    return std::nullopt;
  }

  std::optional<std::pair<ImmersedCoupling::CellIterator, Point<3>>>
  ImmersedCoupling::choose(const std::vector<CellIterator> &candidates,
                           const Point<3>                  &p) const
  {
    // A point clearly inside one cell is in no other; one on a face or an
    // edge (within round-off) goes to the candidate of lowest index, so
    // that the choice does not depend on where the search started (a
    // resumed run places its points afresh and must find the same cells).
    std::optional<std::pair<CellIterator, Point<3>>> best;
    for (const CellIterator &cell : candidates)
      if (const auto reference = reference_in(cell, p))
        {
          if (GeometryInfo<3>::is_inside_unit_cell(*reference, -clearly_inside))
            return std::make_pair(cell, *reference);
          if (!best ||
              cell->active_cell_index() < best->first->active_cell_index())
            best = std::make_pair(cell, *reference);
        }
    return best;
  }

  std::optional<std::pair<ImmersedCoupling::CellIterator, Point<3>>>
  ImmersedCoupling::locate_near(const CellIterator &cell,
                                const Point<3>     &p) const
  {
    std::vector<CellIterator> candidates{cell};
    const auto               &cells_at_vertex = cache.get_vertex_to_cell_map();
    for (const unsigned int v : cell->vertex_indices())
      for (const auto &neighbor : cells_at_vertex[cell->vertex_index(v)])
        if (std::find(candidates.begin(), candidates.end(), neighbor) ==
            candidates.end())
          candidates.push_back(neighbor);
    for (const CellIterator &candidate : candidates)
      if (const auto reference = reference_in(candidate, p))
        if (GeometryInfo<3>::is_inside_unit_cell(*reference, -clearly_inside))
          return std::make_pair(candidate, *reference);
    // On a face or an edge: the search of every rank decides (place()),
    // as it would for a point placed afresh.
    return std::nullopt;
  }

  std::optional<std::pair<ImmersedCoupling::CellIterator, Point<3>>>
  ImmersedCoupling::locate_anywhere(const Point<3> &p) const
  {
    namespace bgi = boost::geometry::index;
    std::vector<CellIterator> candidates;
    for (const auto &[box, cell] :
         cache.get_locally_owned_cell_bounding_boxes_rtree() |
           bgi::adaptors::queried(bgi::intersects(p)))
      candidates.push_back(cell);
    return choose(candidates, p);
  }

  void
  ImmersedCoupling::place(const std::vector<Point<3>> &points)
  {
    const MPI_Comm     communicator = triangulation.get_communicator();
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    n_membrane_points       = points.size();
    owner_cell.resize(n_membrane_points, triangulation.end());
    reference_points.resize(n_membrane_points);

    std::vector<Point<3>> wrapped(n_membrane_points);
    for (unsigned int i = 0; i < n_membrane_points; ++i)
      wrapped[i] = wrap_into_segment(points[i], period);
    fluid_ranks = claim_points(wrapped);
    ++placements;
    for (unsigned int i = 0; i < n_membrane_points; ++i)
      {
        if (fluid_ranks[i] == nobody)
          throw std::runtime_error(
            "membrane point " + std::to_string(i) + " at (" +
            std::to_string(points[i][0]) + ", " + std::to_string(points[i][1]) +
            ", " + std::to_string(points[i][2]) +
            ") µm lies outside the fluid domain: a cell has left it "
            "or touched its wall.");
        if (fluid_ranks[i] != rank)
          owner_cell[i] = triangulation.end();
      }

    group_points_by_cell();
    take_shape_values();
  }

  std::vector<unsigned int>
  ImmersedCoupling::claim_points(const std::vector<Point<3>> &wrapped)
  {
    const MPI_Comm     communicator = triangulation.get_communicator();
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    // First the points this rank held, near where they were; then every
    // rank looks for the points nobody kept among its own cells. The
    // lowest rank that found a point keeps it.
    std::vector<unsigned int> claims(n_membrane_points, nobody);
    const auto keep = [&](const unsigned int i, const auto &found) {
      if (found)
        {
          owner_cell[i]       = found->first;
          reference_points[i] = found->second;
          claims[i]           = rank;
        }
      else
        owner_cell[i] = triangulation.end();
    };
    for (unsigned int i = 0; i < n_membrane_points; ++i)
      if (owner_cell[i] != triangulation.end())
        keep(i, locate_near(owner_cell[i], wrapped[i]));
    Utilities::MPI::min(claims, communicator, claims);
    // The same on every rank now; the second minimum takes only the points
    // nobody kept, whose list every rank knows alike.
    std::vector<unsigned int> unclaimed;
    for (unsigned int i = 0; i < n_membrane_points; ++i)
      if (claims[i] == nobody)
        unclaimed.push_back(i);
    if (!unclaimed.empty())
      {
        std::vector<unsigned int> found(unclaimed.size());
        for (unsigned int k = 0; k < unclaimed.size(); ++k)
          {
            keep(unclaimed[k], locate_anywhere(wrapped[unclaimed[k]]));
            found[k] = claims[unclaimed[k]];
          }
        Utilities::MPI::min(found, communicator, found);
        for (unsigned int k = 0; k < unclaimed.size(); ++k)
          claims[unclaimed[k]] = found[k];
      }
    return claims;
  }

  void
  ImmersedCoupling::group_points_by_cell()
  {
    points_by_cell.clear();
    for (unsigned int i = 0; i < n_membrane_points; ++i)
      if (owner_cell[i] != triangulation.end())
        points_by_cell.push_back(i);
    std::sort(points_by_cell.begin(),
              points_by_cell.end(),
              [this](const unsigned int a, const unsigned int b) {
                return owner_cell[a]->active_cell_index() <
                       owner_cell[b]->active_cell_index();
              });
    point_cells.clear();
    cell_start.clear();
    for (unsigned int k = 0; k < points_by_cell.size(); ++k)
      if (k == 0 ||
          owner_cell[points_by_cell[k]] != owner_cell[points_by_cell[k - 1]])
        {
          point_cells.push_back(owner_cell[points_by_cell[k]]);
          cell_start.push_back(k);
        }
    cell_start.push_back(points_by_cell.size());
  }

  void
  ImmersedCoupling::take_shape_values()
  {
    const FiniteElement<3> &fe = dof_handler.get_fe();
    shape_values.resize(points_by_cell.size() *
                        velocity_shape_functions.size());
    auto phi = shape_values.begin();
    for (const unsigned int i : points_by_cell)
      for (const auto &[k, c] : velocity_shape_functions)
        *phi++ = fe.shape_value_component(k, reference_points[i], c);
  }

  template <typename CellFunction>
  void
  ImmersedCoupling::for_each_point_cell(const CellFunction &f) const
  {
    std::vector<types::global_dof_index> dofs(
      dof_handler.get_fe().n_dofs_per_cell());
    for (unsigned int c = 0; c < point_cells.size(); ++c)
      {
        const DoFHandler<3>::active_cell_iterator dof_cell(*point_cells[c],
                                                           &dof_handler);
        dof_cell->get_dof_indices(dofs);
        f(dofs, cell_start[c], cell_start[c + 1]);
      }
  }

  void
  ImmersedCoupling::spread(const std::vector<Tensor<1, 3>> &forces,
                           const AffineConstraints<double> &constraints,
                           VelocityVector                  &load) const
  {
    spread_power(forces, 1, constraints, load);
  }

  void
  ImmersedCoupling::spread_squares(const std::vector<Tensor<1, 3>> &weights,
                                   const AffineConstraints<double> &constraints,
                                   VelocityVector                  &load) const
  {
    spread_power(weights, 2, constraints, load);
  }

  void
  ImmersedCoupling::spread_power(const std::vector<Tensor<1, 3>> &forces,
                                 const unsigned int               power,
                                 const AffineConstraints<double> &constraints,
                                 VelocityVector                  &load) const
  {
    AssertDimension(forces.size(), n_membrane_points);
    Vector<double> cell_load(dof_handler.get_fe().n_dofs_per_cell());
    auto           phi = shape_values.begin();
    for_each_point_cell(
      [&](const auto &dofs, const unsigned int first, const unsigned int last) {
        cell_load = 0.;
        for (unsigned int k = first; k < last; ++k)
          for (const auto &[j, c] : velocity_shape_functions)
            {
              const double value = *phi++;
              cell_load[j] += forces[points_by_cell[k]][c] *
                              (power == 1 ? value : value * value);
            }
        constraints.distribute_local_to_global(cell_load, dofs, load);
      });
    load.compress(VectorOperation::add);
  }

  std::vector<Tensor<1, 3>>
  ImmersedCoupling::evaluate(const VelocityVector &velocity_field) const
  {
    std::vector<Tensor<1, 3>> velocity(n_membrane_points);
    std::vector<double> cell_values(dof_handler.get_fe().n_dofs_per_cell());
    auto                phi = shape_values.begin();
    for_each_point_cell(
      [&](const auto &dofs, const unsigned int first, const unsigned int last) {
        for (const auto &[j, c] : velocity_shape_functions)
          cell_values[j] = velocity_field(dofs[j]);
        for (unsigned int k = first; k < last; ++k)
          for (const auto &[j, c] : velocity_shape_functions)
            velocity[points_by_cell[k]][c] += cell_values[j] * *phi++;
      });
    return velocity;
  }

  std::vector<Tensor<1, 3>>
  ImmersedCoupling::interpolate(const VelocityVector &velocity_field) const
  {
    // Each point is on one rank; the others add zero.
    std::vector<Tensor<1, 3>> velocity = evaluate(velocity_field);
    if (velocity.empty())
      return velocity;
    Utilities::MPI::sum(
      ArrayView<const double>(&velocity[0][0], 3 * velocity.size()),
      triangulation.get_communicator(),
      ArrayView<double>(&velocity[0][0], 3 * velocity.size()));
    return velocity;
  }

  const std::vector<unsigned int> &
  ImmersedCoupling::point_ranks() const
  {
    return fluid_ranks;
  }

  MPI_Comm
  ImmersedCoupling::get_communicator() const
  {
    return triangulation.get_communicator();
  }

  unsigned int
  ImmersedCoupling::n_placements() const
  {
    return placements;
  }

  unsigned int
  ImmersedCoupling::n_points() const
  {
    return n_membrane_points;
  }

  unsigned int
  ImmersedCoupling::n_locally_owned_points() const
  {
    return points_by_cell.size();
  }

  const std::vector<unsigned int> &
  ImmersedCoupling::locally_owned_point_indices() const
  {
    return points_by_cell;
  }

  double
  ImmersedCoupling::mesh_size_at_points() const
  {
    double h = 0.;
    for (const CellIterator &cell : point_cells)
      h = std::max(h, cell->minimum_vertex_distance());
    return Utilities::MPI::max(h, triangulation.get_communicator());
  }
} // namespace rbc_ifem

#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  ImmersedCoupling::ImmersedCoupling(const Triangulation<3> &triangulation,
                                     const Mapping<3>       &mapping,
                                     const DoFHandler<3> &velocity_dof_handler,
                                     const std::optional<double> &period)
    : triangulation(triangulation)
    , dof_handler(velocity_dof_handler)
    , period(period)
    , cache(triangulation, mapping)
    , particles(triangulation, mapping)
  {
    const FiniteElement<3> &fe = dof_handler.get_fe();
    for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
      velocity_shape_functions.emplace_back(
        k, fe.system_to_component_index(k).first);
  }

  void
  ImmersedCoupling::place(const std::vector<Point<3>> &points)
  {
    particles.clear_particles();
    cell_hints.resize(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        const Point<3> point = wrap_into_segment(points[i], period);
        const auto [cell, reference] =
          GridTools::find_active_cell_around_point(cache, point, cell_hints[i]);
        if (cell == triangulation.end())
          throw std::runtime_error(
            "membrane point " + std::to_string(i) + " at (" +
            std::to_string(points[i][0]) + ", " + std::to_string(points[i][1]) +
            ", " + std::to_string(points[i][2]) +
            ") µm lies outside the fluid domain: a cell has left it "
            "or touched its wall.");
        cell_hints[i] = cell;
        if (cell->is_locally_owned())
          particles.insert_particle(point, reference, i, cell);
      }
    n_membrane_points = points.size();

    const FiniteElement<3> &fe = dof_handler.get_fe();
    shape_values.clear();
    shape_values.reserve(particles.n_locally_owned_particles() *
                         velocity_shape_functions.size());
    for_each_particle_cell([&](const auto &, const auto &in_cell) {
      for (const auto &p : in_cell)
        for (const auto &[k, c] : velocity_shape_functions)
          shape_values.push_back(
            fe.shape_value_component(k, p.get_reference_location(), c));
    });
  }

  template <typename CellFunction>
  void
  ImmersedCoupling::for_each_particle_cell(const CellFunction &f) const
  {
    std::vector<types::global_dof_index> dofs(
      dof_handler.get_fe().n_dofs_per_cell());
    // Particles are stored cell by cell: take one cell's at a time.
    auto particle = particles.begin();
    while (particle != particles.end())
      {
        const auto cell = particle->get_surrounding_cell();
        const typename DoFHandler<3>::active_cell_iterator dof_cell(
          *cell, &dof_handler);
        dof_cell->get_dof_indices(dofs);
        const auto in_cell = particles.particles_in_cell(cell);
        f(dofs, in_cell);
        particle = in_cell.end();
      }
  }

  void
  ImmersedCoupling::spread(const std::vector<Tensor<1, 3>> &forces,
                           const AffineConstraints<double> &constraints,
                           VelocityVector                  &load) const
  {
    AssertDimension(forces.size(), n_membrane_points);
    Vector<double> cell_load(dof_handler.get_fe().n_dofs_per_cell());
    auto           phi = shape_values.begin();
    for_each_particle_cell([&](const auto &dofs, const auto &in_cell) {
      cell_load = 0.;
      for (const auto &p : in_cell)
        for (const auto &[k, c] : velocity_shape_functions)
          cell_load[k] += forces[p.get_id()][c] * *phi++;
      constraints.distribute_local_to_global(cell_load, dofs, load);
    });
    load.compress(VectorOperation::add);
  }

  std::vector<Tensor<1, 3>>
  ImmersedCoupling::interpolate(const VelocityVector &velocity_field) const
  {
    // Each point is on one rank; the others add zero.
    std::vector<double> velocity(3 * n_membrane_points, 0.);
    std::vector<double> cell_values(dof_handler.get_fe().n_dofs_per_cell());
    auto                phi = shape_values.begin();
    for_each_particle_cell([&](const auto &dofs, const auto &in_cell) {
      for (const auto &[k, c] : velocity_shape_functions)
        cell_values[k] = velocity_field(dofs[k]);
      for (const auto &p : in_cell)
        for (const auto &[k, c] : velocity_shape_functions)
          velocity[3 * p.get_id() + c] += cell_values[k] * *phi++;
    });
    Utilities::MPI::sum(velocity, triangulation.get_communicator(), velocity);
    std::vector<Tensor<1, 3>> result(n_membrane_points);
    for (unsigned int i = 0; i < n_membrane_points; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        result[i][c] = velocity[3 * i + c];
    return result;
  }

  unsigned int
  ImmersedCoupling::n_points() const
  {
    return n_membrane_points;
  }

  double
  ImmersedCoupling::mesh_size_at_points() const
  {
    // Every rank knows every point's cell: no communication.
    double h = 0.;
    for (const auto &cell : cell_hints)
      h = std::max(h, cell->minimum_vertex_distance());
    return h;
  }

  const Particles::ParticleHandler<3> &
  ImmersedCoupling::get_particle_handler() const
  {
    return particles;
  }
} // namespace rbc_ifem

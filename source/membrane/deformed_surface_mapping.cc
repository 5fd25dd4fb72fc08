#include <rbc_ifem/membrane/deformed_surface_mapping.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/fe/fe_q.h>

namespace rbc_ifem
{
  namespace
  {
    /// The degree of the mapping: the reference meshes' MappingQ's.
    constexpr unsigned int degree = 2;
  } // namespace

  DeformedSurfaceMapping::DeformedSurfaceMapping(
    const std::vector<const Triangulation<2, 3> *> &surfaces,
    const std::vector<const Membrane *>            &membranes,
    const std::vector<Vector<double>>              &positions)
    : DeformedSurfaceMapping(
        surfaces,
        [&](const unsigned int c) {
          AssertIndexRange(c, membranes.size());
          // Not owned: the caller's membranes outlive the making.
          return std::shared_ptr<const Membrane>(
            std::shared_ptr<const Membrane>(), membranes[c]);
        },
        positions)
  {
    AssertDimension(surfaces.size(), membranes.size());
  }

  DeformedSurfaceMapping::DeformedSurfaceMapping(
    const std::vector<const Triangulation<2, 3> *> &surfaces,
    const std::function<std::shared_ptr<const Membrane>(unsigned int)>
                                      &membrane_of,
    const std::vector<Vector<double>> &positions)
    : MappingQ<2, 3>(degree)
  {
    AssertDimension(surfaces.size(), positions.size());
    // MappingQ orders its support points as FE_Q numbers its nodes:
    // vertices, the lines' interior points, the cell's. (At degree 2 every
    // line has one, so the lines' orientations do not matter.)
    const std::vector<Point<2>> unit_points =
      FE_Q<2>(degree).get_unit_support_points();
    auto points = std::make_shared<SupportPoints>();
    for (unsigned int c = 0; c < surfaces.size(); ++c)
      {
        const std::shared_ptr<const Membrane> membrane = membrane_of(c);
        const DoFHandler<2, 3>    &dof_handler = membrane->get_dof_handler();
        const FiniteElement<2, 3> &fe          = dof_handler.get_fe();
        AssertDimension(surfaces[c]->n_active_cells(),
                        dof_handler.get_triangulation().n_active_cells());
        Vector<double> displacement(positions[c]);
        displacement -= membrane->reference_positions();
        std::vector<std::vector<Point<3>>> &cell_points =
          (*points)[surfaces[c]];
        cell_points.resize(surfaces[c]->n_active_cells());
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            // The reference shape, from the reference mesh's manifolds.
            std::vector<Point<3>> &p = cell_points[cell->active_cell_index()];
            p = MappingQ<2, 3>::compute_mapping_support_points(cell);
            cell->get_dof_indices(dofs);
            for (unsigned int k = 0; k < unit_points.size(); ++k)
              for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
                p[k][fe.system_to_component_index(j).first] +=
                  fe.shape_value(j, unit_points[k]) * displacement[dofs[j]];
          }
      }
    support_points = std::move(points);
  }

  std::unique_ptr<Mapping<2, 3>>
  DeformedSurfaceMapping::clone() const
  {
    return std::make_unique<DeformedSurfaceMapping>(*this);
  }

  std::vector<Point<3>>
  DeformedSurfaceMapping::compute_mapping_support_points(
    const typename Triangulation<2, 3>::cell_iterator &cell) const
  {
    const auto surface = support_points->find(&cell->get_triangulation());
    AssertThrow(surface != support_points->end() && cell->is_active(),
                ExcMessage("DeformedSurfaceMapping maps the active cells of "
                           "the surfaces it was built for only."));
    return surface->second[cell->active_cell_index()];
  }
} // namespace rbc_ifem

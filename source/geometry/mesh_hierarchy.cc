#include <rbc_ifem/geometry/mesh_hierarchy.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

namespace rbc_ifem
{
  namespace
  {
    /// An empty mesh of the kind of @p mesh (parallel::shared or serial).
    std::shared_ptr<Triangulation<3>>
    empty_like(const Triangulation<3> &mesh)
    {
      if (const auto shared =
            dynamic_cast<const parallel::shared::Triangulation<3> *>(&mesh))
        return std::make_shared<parallel::shared::Triangulation<3>>(
          shared->get_communicator(),
          shared->get_mesh_smoothing(),
          shared->with_artificial_cells(),
          parallel::shared::Triangulation<3>::partition_metis);
      return std::make_shared<Triangulation<3>>(mesh.get_mesh_smoothing());
    }

    /**
     * A new mesh with the coarse cells and the manifolds of @p fine, refined
     * as @p fine is. The manifolds are attached to the coarse mesh, as when
     * @p fine was made, and place the new vertices where they are in @p fine.
     */
    std::shared_ptr<Triangulation<3>>
    rebuild(const Triangulation<3> &fine)
    {
      auto mesh = empty_like(fine);
      const auto [vertices, cells, faces] =
        GridTools::get_coarse_mesh_description(fine);
      mesh->create_triangulation(vertices, cells, faces);
      for (const types::manifold_id id : fine.get_manifold_ids())
        {
          if (id == numbers::flat_manifold_id)
            continue;
          if (dynamic_cast<const TransfiniteInterpolationManifold<3> *>(
                &fine.get_manifold(id)))
            {
              TransfiniteInterpolationManifold<3> transfinite;
              transfinite.initialize(*mesh);
              mesh->set_manifold(id, transfinite);
            }
          else
            mesh->set_manifold(id, fine.get_manifold(id));
        }
      for (unsigned int level = 0; level + 1 < fine.n_global_levels(); ++level)
        {
          for (const auto &cell : mesh->active_cell_iterators_on_level(level))
            if (fine.create_cell_iterator(cell->id())->has_children())
              cell->set_refine_flag();
          mesh->execute_coarsening_and_refinement();
        }
      return mesh;
    }
  } // namespace

  std::vector<std::shared_ptr<const Triangulation<3>>>
  global_coarsening_sequence(const Triangulation<3> &fine)
  {
    const unsigned int n_levels = fine.n_global_levels();
    std::vector<std::shared_ptr<const Triangulation<3>>> levels(n_levels - 1);
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      {
        std::shared_ptr<Triangulation<3>> level = rebuild(fine);
        for (unsigned int k = l + 1; k < n_levels; ++k)
          level->coarsen_global();
        levels[l] = level;
      }
    return levels;
  }
} // namespace rbc_ifem

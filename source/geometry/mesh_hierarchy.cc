#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>
#include <rbc_ifem/geometry/mesh_zone.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria_description.h>

#include <algorithm>
#include <optional>
#include <utility>

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

  namespace
  {
    /// The length along x of the coarse mesh @p mesh.
    double
    x_length(const Triangulation<3> &mesh)
    {
      double low = mesh.get_vertices()[0][0], high = low;
      for (const Point<3> &vertex : mesh.get_vertices())
        {
          low  = std::min(low, vertex[0]);
          high = std::max(high, vertex[0]);
        }
      return high - low;
    }

    /**
     * Build @p mesh on every rank from the rank's own part of the serial
     * mesh: @p coarse the whole coarse mesh, @p refine its zone's cells
     * (MeshZone, its slabs balanced by @p weights if given), coarsened
     * @p n_coarsenings times for a multigrid level.
     */
    void
    distribute(
      parallel::fullydistributed::Triangulation<3>                    &mesh,
      const std::function<void(Triangulation<3> &)>                   &coarse,
      const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
      const bool                                                       periodic,
      const unsigned int         n_coarsenings,
      const std::vector<double> &weights = {})
    {
      const MPI_Comm     communicator = mesh.get_communicator();
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
      // Hanging nodes need the description's levels, which limit the level
      // difference at vertices to one.
      Triangulation<3> serial(
        Triangulation<3>::limit_level_difference_at_vertices);
      coarse(serial);
      const MeshZone zone(serial,
                          rank,
                          Utilities::MPI::n_mpi_processes(communicator),
                          periodic ? std::optional<double>(x_length(serial)) :
                                     std::nullopt,
                          weights);
      refine(serial, zone);
      serial.coarsen_global(n_coarsenings);
      zone.mark_owners(serial);
      const auto description = TriangulationDescription::Utilities::
        create_description_from_triangulation(
          serial,
          communicator,
          TriangulationDescription::Settings::construct_multigrid_hierarchy,
          rank);
      create_capillary_mesh(mesh, description);
      if (periodic)
        add_end_periodicity(mesh);
    }

  } // namespace

  std::vector<std::shared_ptr<const Triangulation<3>>>
  create_distributed_mesh_hierarchy(
    parallel::fullydistributed::Triangulation<3>                    &fine,
    const std::function<void(Triangulation<3> &)>                   &coarse,
    const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
    const bool                                                       periodic,
    const std::vector<double>                                       &weights)
  {
    distribute(fine, coarse, refine, periodic, 0, weights);
    const unsigned int n_levels = fine.n_global_levels();
    std::vector<std::shared_ptr<const Triangulation<3>>> levels;
    for (unsigned int l = 0; l + 1 < n_levels; ++l)
      {
        auto level =
          std::make_shared<parallel::fullydistributed::Triangulation<3>>(
            fine.get_communicator());
        distribute(*level, coarse, refine, periodic, n_levels - 1 - l, weights);
        levels.push_back(level);
      }
    return levels;
  }

  void
  create_distributed_mesh(
    parallel::fullydistributed::Triangulation<3>                    &mesh,
    const std::function<void(Triangulation<3> &)>                   &coarse,
    const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
    const bool                                                       periodic,
    const std::vector<double>                                       &weights)
  {
    distribute(mesh, coarse, refine, periodic, 0, weights);
  }

  std::vector<double>
  fine_cells_per_coarse_cell(
    const MPI_Comm                                 communicator,
    const std::function<void(Triangulation<3> &)> &coarse,
    const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
    const bool                                                       periodic)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
    Triangulation<3>   serial(
      Triangulation<3>::limit_level_difference_at_vertices);
    coarse(serial);
    // The slab alone: the counts weigh the slabs, and need not be exact
    // next to their ends.
    const MeshZone slab =
      MeshZone(serial,
               rank,
               Utilities::MPI::n_mpi_processes(communicator),
               periodic ? std::optional<double>(x_length(serial)) :
                          std::nullopt)
        .slab_only();
    refine(serial, slab);
    std::vector<double> counts(serial.n_cells(0), 0.);
    for (const auto &cell : serial.active_cell_iterators())
      if (slab.owner(cell) == rank)
        counts[cell->id().get_coarse_cell_id()] += 1.;
    std::vector<double> sums(counts.size());
    Utilities::MPI::sum(make_array_view(std::as_const(counts)),
                        communicator,
                        make_array_view(sums));
    return sums;
  }
} // namespace rbc_ifem

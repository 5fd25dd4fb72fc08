#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/diffusion/cut_cell_geometry.h>
#include <rbc_ifem/diffusion/uptake_mesh.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/shared_tria.h>

#include <optional>

namespace rbc_ifem
{
  namespace
  {
    /**
     * The cell @p id of @p mesh, if its coarse cell lies in @p zone and the
     * mesh is refined that far there: beyond a rank's slab and its ghost
     * layer, its zone's mesh need not hold every cell of the whole mesh.
     */
    std::optional<Triangulation<3>::cell_iterator>
    find_cell(const Triangulation<3> &mesh,
              const CellId           &id,
              const MeshZone         &zone)
    {
      Triangulation<3>::cell_iterator cell(&mesh, 0, id.get_coarse_cell_id());
      if (!zone.contains(cell))
        return std::nullopt;
      for (const std::uint8_t child : id.get_child_indices())
        {
          if (!cell->has_children())
            return std::nullopt;
          cell = cell->child(child);
        }
      return cell;
    }

    /// Refine those of the cells @p cells of @p mesh that @p zone holds
    /// (find_cell()), and their face neighbours.
    void
    refine_cells_and_neighbors(Triangulation<3>          &mesh,
                               const std::vector<CellId> &cells,
                               const MeshZone            &zone)
    {
      for (const CellId &id : cells)
        if (const auto cell = find_cell(mesh, id, zone);
            cell && (*cell)->is_active())
          {
            (*cell)->set_refine_flag();
            for (const unsigned int f : (*cell)->face_indices())
              if (!(*cell)->at_boundary(f) && (*cell)->neighbor(f)->is_active())
                (*cell)->neighbor(f)->set_refine_flag();
          }
      mesh.execute_coarsening_and_refinement();
    }
  } // namespace

  UptakeMesh::UptakeMesh(const GeometryParameters &geometry,
                         const MeshParameters     &mesh_parameters,
                         const DiffusionMethod     method,
                         const MPI_Comm            communicator,
                         TimerOutput              &timer)
    : geometry(geometry)
    , mesh_parameters(mesh_parameters)
    , method(method)
    , communicator(communicator)
    , timer(timer)
  {}

  void
  UptakeMesh::build(
    const MembraneSurfaces                              &surfaces,
    const std::function<void(const parallel::TriangulationBase<3> &,
                             const bool refine_ridges)> &set_up)
  {
    band_points = points_in_segment(surfaces.vertices(), geometry.period());
    refinements.clear();
    make();
    bool refine_ridges = true;
    for (;;)
      try
        {
          set_up(*mesh, refine_ridges);
          return;
        }
      catch (const UnresolvedCutCells &e)
        {
          const unsigned int refinement = refinements.size();
          if (refinement < mesh_parameters.diffusion_gap_refinements)
            {
              refinements.push_back(e.cells);
              make();
              continue;
            }
          if (e.membranes)
            throw InputError(
              "Layout",
              "cells " + std::to_string(e.membranes->first) + " and " +
                std::to_string(e.membranes->second),
              "these two membranes pass through one cell of the "
              "diffusion mesh after " +
                std::to_string(refinement) +
                " local refinements (they are closer than the mesh "
                "resolves): raise Mesh/Diffusion gap refinements or "
                "Mesh/Diffusion band refinements, or move the cells "
                "apart.");
          refine_ridges = false;
        }
  }

  const parallel::TriangulationBase<3> &
  UptakeMesh::triangulation() const
  {
    return *mesh;
  }

  void
  UptakeMesh::make_coarse(Triangulation<3> &coarse) const
  {
    create_diffusion_mesh(coarse, geometry, 0);
    if (geometry.period())
      add_end_periodicity(coarse);
  }

  void
  UptakeMesh::refine(Triangulation<3> &mesh, const MeshZone &zone) const
  {
    zone.refine_global(mesh, mesh_parameters.diffusion_global_refinements);
    const auto match_ends = [this, &mesh]() {
      if (geometry.period())
        match_end_refinement(mesh);
    };
    refine_near_points(mesh,
                       band_points,
                       mesh_parameters.band_width,
                       mesh_parameters.diffusion_band_refinements,
                       zone);
    // After each step, as the mesh was whose cells the next step names.
    match_ends();
    for (const std::vector<CellId> &cells : refinements)
      {
        refine_cells_and_neighbors(mesh, cells, zone);
        match_ends();
      }
  }

  void
  UptakeMesh::make()
  {
    TimerOutput::Scope scope(timer, "diffusion mesh");
    mesh.reset();
    if (method != DiffusionMethod::cut_cell)
      {
        auto shared = std::make_unique<parallel::shared::Triangulation<3>>(
          communicator,
          Triangulation<3>::none,
          false,
          parallel::shared::Triangulation<3>::partition_metis);
        make_coarse(*shared);
        refine(*shared, MeshZone());
        mesh = std::move(shared);
        return;
      }
    const auto coarse = [this](Triangulation<3> &coarse) {
      make_coarse(coarse);
    };
    const auto refine_zone = [this](Triangulation<3> &serial,
                                    const MeshZone   &zone) {
      refine(serial, zone);
    };
    const bool periodic = geometry.period().has_value();
    // Counted again on every attempt: the cells an attempt refines can be
    // many, all near one membrane (a folded rim), and in one slab.
    const std::vector<double> weights =
      Utilities::MPI::n_mpi_processes(communicator) > 1 ?
        fine_cells_per_coarse_cell(communicator,
                                   coarse,
                                   refine_zone,
                                   periodic) :
        std::vector<double>();
    auto distributed =
      std::make_unique<parallel::fullydistributed::Triangulation<3>>(
        communicator);
    create_distributed_mesh(
      *distributed, coarse, refine_zone, periodic, weights);
    mesh = std::move(distributed);
  }

  types::global_vertex_index
  UptakeMesh::n_global_vertices() const
  {
    // Each vertex is counted by the lowest rank whose cells hold it.
    std::vector<types::subdomain_id> lowest(mesh->n_vertices(),
                                            numbers::invalid_subdomain_id);
    for (const auto &cell : mesh->active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          lowest[cell->vertex_index(v)] =
            std::min(lowest[cell->vertex_index(v)], cell->subdomain_id());
    const types::subdomain_id  rank = mesh->locally_owned_subdomain();
    types::global_vertex_index n    = 0;
    for (const types::subdomain_id owner : lowest)
      n += (owner == rank);
    return Utilities::MPI::sum(n, communicator);
  }
  std::unique_ptr<CutCellGeometry>
  build_cut_cell_geometry(UptakeMesh               &mesh,
                          const GeometryParameters &geometry,
                          const MembraneSurfaces   &surfaces,
                          const unsigned int        degree,
                          const bool                separate_insides,
                          TimerOutput              &timer)
  {
    std::shared_ptr<const MembraneDistance> distance;
    {
      TimerOutput::Scope scope(timer, "diffusion: membrane sampling");
      distance = std::make_shared<MembraneDistance>(surfaces.meshes(),
                                                    surfaces.mapping(),
                                                    geometry.period());
    }
    std::unique_ptr<CutCellGeometry> cut_cells;
    mesh.build(surfaces,
               [&](const parallel::TriangulationBase<3> &triangulation,
                   const bool                            refine_ridges) {
                 CutCellGeometry::Options options;
                 options.refine_ridges    = refine_ridges;
                 options.separate_insides = separate_insides;
                 cut_cells =
                   std::make_unique<CutCellGeometry>(triangulation,
                                                     surfaces,
                                                     distance,
                                                     degree,
                                                     geometry.period(),
                                                     options,
                                                     timer);
               });
    return cut_cells;
  }
} // namespace rbc_ifem

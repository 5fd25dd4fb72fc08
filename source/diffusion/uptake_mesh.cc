#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/diffusion/cut_cell_geometry.h>
#include <rbc_ifem/diffusion/uptake_mesh.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

namespace rbc_ifem
{
  namespace
  {
    /// Refine the cells @p cells of @p mesh and their face neighbours.
    void
    refine_cells_and_neighbors(Triangulation<3>          &mesh,
                               const std::vector<CellId> &cells)
    {
      for (const CellId &id : cells)
        {
          const auto cell = mesh.create_cell_iterator(id);
          cell->set_refine_flag();
          for (const unsigned int f : cell->face_indices())
            if (!cell->at_boundary(f) && cell->neighbor(f)->is_active())
              cell->neighbor(f)->set_refine_flag();
        }
      mesh.execute_coarsening_and_refinement();
    }

    /**
     * For @p overlap[a][b], the cells that new part a shares with old part
     * b: the old number of each new part, chosen greedily, the largest
     * overlap first (the best numbering on two parts).
     */
    std::vector<types::subdomain_id>
    numbering_that_keeps(const std::vector<std::vector<unsigned int>> &overlap)
    {
      const unsigned int               n_parts = overlap.size();
      std::vector<types::subdomain_id> number(n_parts,
                                              numbers::invalid_subdomain_id);
      std::vector<bool>                taken(n_parts, false);
      for (unsigned int k = 0; k < n_parts; ++k)
        {
          unsigned int best_new = 0, best_old = 0;
          bool         found = false;
          for (unsigned int a = 0; a < n_parts; ++a)
            for (unsigned int b = 0; b < n_parts; ++b)
              if (number[a] == numbers::invalid_subdomain_id && !taken[b] &&
                  (!found || overlap[a][b] > overlap[best_new][best_old]))
                {
                  best_new = a;
                  best_old = b;
                  found    = true;
                }
          number[best_new] = best_old;
          taken[best_old]  = true;
        }
      return number;
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
    partition.clear();
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
  UptakeMesh::make_serial(Triangulation<3> &serial) const
  {
    create_diffusion_mesh(serial,
                          geometry,
                          mesh_parameters.diffusion_global_refinements);
    const auto match_ends = [this, &serial]() {
      if (geometry.period())
        match_end_refinement(serial);
    };
    if (geometry.period())
      add_end_periodicity(serial);
    refine_near_points(serial,
                       band_points,
                       mesh_parameters.band_width,
                       mesh_parameters.diffusion_band_refinements);
    // After each step, as the mesh was whose cells the next step names.
    match_ends();
    for (const std::vector<CellId> &cells : refinements)
      {
        refine_cells_and_neighbors(serial, cells);
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
        make_serial(*shared);
        mesh = std::move(shared);
        return;
      }
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    // Hanging nodes need the description's levels, which limit the level
    // difference at vertices to one.
    const auto description = TriangulationDescription::Utilities::
      create_description_from_triangulation_in_groups<3, 3>(
        [this](Triangulation<3> &serial) { make_serial(serial); },
        [this, n_ranks](Triangulation<3> &serial,
                        const MPI_Comm &,
                        const unsigned int) {
          partition_like(serial, n_ranks);
        },
        communicator,
        n_ranks,
        Triangulation<3>::none,
        TriangulationDescription::Settings::construct_multigrid_hierarchy);
    auto distributed =
      std::make_unique<parallel::fullydistributed::Triangulation<3>>(
        communicator);
    create_capillary_mesh(*distributed, description);
    if (geometry.period())
      add_end_periodicity(*distributed);
    mesh = std::move(distributed);
  }

  void
  UptakeMesh::partition_like(Triangulation<3>  &serial,
                             const unsigned int n_parts)
  {
    GridTools::partition_triangulation(n_parts, serial);
    if (!partition.empty())
      {
        // overlap[new part][old part]: cells, counted on the finer mesh.
        std::vector<std::vector<unsigned int>> overlap(
          n_parts, std::vector<unsigned int>(n_parts, 0));
        for (const auto &cell : serial.active_cell_iterators())
          {
            Triangulation<3>::cell_iterator ancestor = cell;
            while (partition.count(ancestor->id()) == 0 &&
                   ancestor->level() > 0)
              ancestor = ancestor->parent();
            if (const auto old = partition.find(ancestor->id());
                old != partition.end())
              ++overlap[cell->subdomain_id()][old->second];
          }
        const std::vector<types::subdomain_id> number =
          numbering_that_keeps(overlap);
        for (const auto &cell : serial.active_cell_iterators())
          cell->set_subdomain_id(number[cell->subdomain_id()]);
      }
    partition.clear();
    for (const auto &cell : serial.active_cell_iterators())
      partition.emplace(cell->id(), cell->subdomain_id());
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
} // namespace rbc_ifem

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/diffusion/cut_cell_diffusion.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/distributed/shared_tria.h>

#include <iomanip>
#include <memory>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// The diffusion mesh of the capillary of @p geometry, refined
    /// @p band_refinements times within Mesh/Band width of the vertices of
    /// @p surfaces.
    void
    make_uptake_mesh(parallel::shared::Triangulation<3> &mesh,
                     const GeometryParameters           &geometry,
                     const MeshParameters               &mesh_parameters,
                     const std::vector<const Triangulation<2, 3> *> &surfaces,
                     const unsigned int band_refinements,
                     TimerOutput       &timer)
    {
      TimerOutput::Scope    scope(timer, "diffusion mesh");
      std::vector<Point<3>> band_points;
      for (const auto *surface : surfaces)
        band_points.insert(band_points.end(),
                           surface->get_vertices().begin(),
                           surface->get_vertices().end());
      create_diffusion_mesh(mesh,
                            geometry,
                            mesh_parameters.diffusion_global_refinements);
      refine_near_points(mesh,
                         points_in_segment(band_points, geometry.period()),
                         mesh_parameters.band_width,
                         band_refinements);
    }

    /// Refine the active cells @p cells of @p mesh and their face
    /// neighbours (the same on every rank: the indices are).
    void
    refine_cells_and_neighbors(parallel::shared::Triangulation<3> &mesh,
                               const std::vector<unsigned int>    &cells)
    {
      std::vector<bool> flagged(mesh.n_active_cells(), false);
      for (const unsigned int index : cells)
        flagged[index] = true;
      for (const auto &cell : mesh.active_cell_iterators())
        if (flagged[cell->active_cell_index()])
          {
            cell->set_refine_flag();
            for (const unsigned int f : cell->face_indices())
              if (!cell->at_boundary(f) && cell->neighbor(f)->is_active())
                cell->neighbor(f)->set_refine_flag();
          }
      mesh.execute_coarsening_and_refinement();
    }

    /// The CO diffusion problem of @p d, set up on @p mesh with the
    /// membranes @p surfaces: everything before the assembly. A mesh too
    /// coarse for the membranes is an InputError naming @p band_refinements,
    /// the refinements of the mesh around them. Cut cells ask for
    /// refinement where the distance has a ridge if @p refine_ridges.
    std::unique_ptr<DiffusionSolver>
    set_up_diffusion(const parallel::shared::Triangulation<3>       &mesh,
                     const GeometryParameters                       &geometry,
                     const DiffusionParameters                      &d,
                     const std::vector<const Triangulation<2, 3> *> &surfaces,
                     const MappingQ<2, 3>                           &mapping,
                     const unsigned int band_refinements,
                     const bool         refine_ridges,
                     const MPI_Comm     communicator,
                     TimerOutput       &timer)
    {
      const auto permeability = [&d](const unsigned int id) {
        return d.permeability(id);
      };
      std::unique_ptr<DiffusionSolver> diffusion;
      if (d.method == DiffusionMethod::cut_cell)
        {
          auto cut_cells = std::make_unique<CutCellDiffusion>(
            d,
            permeability,
            DiffusionBoundary::alveolar_surface,
            communicator,
            timer,
            geometry.period());
          cut_cells->refine_ridges(refine_ridges);
          diffusion = std::move(cut_cells);
        }
      else
        diffusion =
          std::make_unique<CODiffusion>(d,
                                        permeability,
                                        DiffusionBoundary::alveolar_surface,
                                        communicator,
                                        timer,
                                        geometry.period());
      try
        {
          diffusion->setup(mesh, surfaces, mapping);
        }
      catch (const MembranesFinerThanMesh &e)
        {
          std::ostringstream sizes;
          sizes << std::setprecision(2) << "the membrane cells ("
                << e.membrane_cell_size
                << " µm) are finer than the diffusion mesh cells around "
                   "them ("
                << e.volume_cell_size << " µm)";
          throw InputError("Mesh/Diffusion band refinements",
                           std::to_string(band_refinements),
                           sizes.str() +
                             "; the diffusion mesh there must be about as "
                             "fine as the membranes or finer (the "
                             "multiplier's inf-sup condition): raise it, or "
                             "lower Cells/Surface refinements.");
        }
      return diffusion;
    }
  } // namespace

  namespace
  {
    /// The diffusion mesh around @p surfaces and the CO diffusion problem
    /// set up on it: what check_uptake_meshes() and solve_uptake() share.
    struct UptakeSetup
    {
      UptakeSetup(const GeometryParameters  &geometry,
                  const MeshParameters      &mesh_parameters,
                  const DiffusionParameters &d,
                  const std::vector<const Triangulation<2, 3> *> &surfaces,
                  const MappingQ<2, 3>                           &mapping,
                  const unsigned int band_refinements,
                  const MPI_Comm     communicator,
                  TimerOutput       &timer)
        : mesh(communicator,
               Triangulation<3>::none,
               false,
               parallel::shared::Triangulation<3>::partition_metis)
      {
        make_uptake_mesh(
          mesh, geometry, mesh_parameters, surfaces, band_refinements, timer);
        // Cut cells: refine where two membranes share a mesh cell, or the
        // distance to them has a ridge in one, until none does; after the
        // last refinement allowed a shared cell is an error, a ridge is
        // left as the mesh resolves it.
        bool refine_ridges = true;
        for (unsigned int refinement = 0;;)
          try
            {
              diffusion = set_up_diffusion(mesh,
                                           geometry,
                                           d,
                                           surfaces,
                                           mapping,
                                           band_refinements,
                                           refine_ridges,
                                           communicator,
                                           timer);
              return;
            }
          catch (const UnresolvedCutCells &e)
            {
              diffusion.reset();
              if (refinement == mesh_parameters.diffusion_gap_refinements)
                {
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
                  continue;
                }
              refine_cells_and_neighbors(mesh, e.cells);
              ++refinement;
            }
      }

      parallel::shared::Triangulation<3> mesh;
      std::unique_ptr<DiffusionSolver>   diffusion;
    };
  } // namespace

  void
  check_uptake_meshes(const GeometryParameters  &geometry,
                      const MeshParameters      &mesh_parameters,
                      const DiffusionParameters &d,
                      const std::vector<const Triangulation<2, 3> *> &surfaces,
                      const MappingQ<2, 3>                           &mapping,
                      const unsigned int band_refinements,
                      const MPI_Comm     communicator,
                      TimerOutput       &timer)
  {
    UptakeSetup(geometry,
                mesh_parameters,
                d,
                surfaces,
                mapping,
                band_refinements,
                communicator,
                timer);
  }

  Uptake
  solve_uptake(const GeometryParameters                       &geometry,
               const MeshParameters                           &mesh_parameters,
               const DiffusionParameters                      &d,
               const std::vector<const Triangulation<2, 3> *> &surfaces,
               const MappingQ<2, 3>                           &mapping,
               const unsigned int                              band_refinements,
               const MPI_Comm                                  communicator,
               TimerOutput                                    &timer,
               const std::function<void(const DiffusionSolver &)> &write_fields)
  {
    Timer                                     clock;
    const UptakeSetup                         setup(geometry,
                            mesh_parameters,
                            d,
                            surfaces,
                            mapping,
                            band_refinements,
                            communicator,
                            timer);
    const parallel::shared::Triangulation<3> &mesh      = setup.mesh;
    DiffusionSolver                          &diffusion = *setup.diffusion;
    diffusion.assemble();
    diffusion.solve();
    if (write_fields)
      write_fields(diffusion);

    Uptake uptake;
    uptake.dm_total = diffusion.dm_total();
    for (const double flow : diffusion.membrane_flows())
      uptake.dm_cells.push_back(flow / d.alveolar_pressure);
    uptake.n_nodes    = mesh.n_used_vertices();
    uptake.n_cells    = mesh.n_active_cells();
    uptake.n_dofs     = diffusion.n_dofs();
    uptake.iterations = diffusion.n_iterations();
    uptake.seconds    = clock.wall_time();
    return uptake;
  }

  std::string
  dm_header(const unsigned int n_cells)
  {
    std::string header = "time,dm_total";
    for (unsigned int c = 0; c < n_cells; ++c)
      header += ",dm_cell_" + std::to_string(c);
    return header;
  }

  std::string
  dm_row(const double time, const Uptake &uptake)
  {
    CsvRow row;
    row << time << uptake.dm_total;
    for (const double dm : uptake.dm_cells)
      row << dm;
    return row.str();
  }

  void
  UptakeFields::write(const DiffusionSolver &diffusion,
                      const std::string     &directory,
                      const double           time,
                      const unsigned int     counter,
                      const MPI_Comm         communicator,
                      const FieldData       &field_data)
  {
    const DiffusionSolver::OutputFiles files =
      diffusion.write_output(directory, "diffusion", counter, field_data);
    pressure.emplace_back(time, files.pressure);
    membranes.emplace_back(time, files.membranes);
    write_pvd(directory, "diffusion", pressure, communicator);
    write_pvd(directory, "diffusion_membranes", membranes, communicator);
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/diffusion/cut_cell_diffusion.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <iomanip>
#include <map>
#include <memory>
#include <sstream>

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
     * What the uptake mesh is: the capillary's diffusion mesh
     * (Mesh/Diffusion global refinements), refined @p band_refinements times
     * within Mesh/Band width of the vertices of @p surfaces, then each of
     * @p refinements in turn (cells that the level set could not resolve,
     * refined with their neighbours).
     */
    struct UptakeMeshRecipe
    {
      const GeometryParameters                       &geometry;
      const MeshParameters                           &mesh_parameters;
      const std::vector<const Triangulation<2, 3> *> &surfaces;
      const unsigned int                              band_refinements;
      std::vector<std::vector<CellId>>                refinements;

      /// Build it on @p mesh, a serial or a shared triangulation.
      void
      make(Triangulation<3> &mesh) const
      {
        std::vector<Point<3>> band_points;
        for (const auto *surface : surfaces)
          band_points.insert(band_points.end(),
                             surface->get_vertices().begin(),
                             surface->get_vertices().end());
        create_diffusion_mesh(mesh,
                              geometry,
                              mesh_parameters.diffusion_global_refinements);
        if (geometry.period())
          add_end_periodicity(mesh);
        refine_near_points(mesh,
                           points_in_segment(band_points, geometry.period()),
                           mesh_parameters.band_width,
                           band_refinements);
        for (const std::vector<CellId> &cells : refinements)
          refine_cells_and_neighbors(mesh, cells);
      }
    };

    /// The subdomain of each active cell of a serial mesh.
    using Partition = std::map<CellId, types::subdomain_id>;

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

    /**
     * Partition @p serial into @p n_parts by METIS, numbering the parts so
     * that each keeps as many cells of @p previous (the partition of the
     * mesh that @p serial refines, empty if none) as it can; then store the
     * new partition in @p previous. A mesh built again after a failed attempt
     * (refined where the level set could not resolve it) is partitioned
     * afresh and so stays balanced, and METIS cuts it much where it cut the
     * last one, but may number the parts the other way round: numbered so,
     * each rank gets back most of its cells and finds their level set nodes
     * answered already (MembraneDistance remembers them).
     */
    void
    partition_like(Triangulation<3>  &serial,
                   const unsigned int n_parts,
                   Partition         &previous)
    {
      GridTools::partition_triangulation(n_parts, serial);
      if (!previous.empty())
        {
          // overlap[new part][old part]: cells, counted on the finer mesh.
          std::vector<std::vector<unsigned int>> overlap(
            n_parts, std::vector<unsigned int>(n_parts, 0));
          for (const auto &cell : serial.active_cell_iterators())
            {
              Triangulation<3>::cell_iterator ancestor = cell;
              while (previous.count(ancestor->id()) == 0 &&
                     ancestor->level() > 0)
                ancestor = ancestor->parent();
              if (const auto old = previous.find(ancestor->id());
                  old != previous.end())
                ++overlap[cell->subdomain_id()][old->second];
            }
          const std::vector<types::subdomain_id> number =
            numbering_that_keeps(overlap);
          for (const auto &cell : serial.active_cell_iterators())
            cell->set_subdomain_id(number[cell->subdomain_id()]);
        }
      previous.clear();
      for (const auto &cell : serial.active_cell_iterators())
        previous.emplace(cell->id(), cell->subdomain_id());
    }

    /**
     * The uptake mesh of @p recipe on @p communicator: for cut cells fully
     * distributed (rank 0 builds it and sends each rank its cells and their
     * ghost layer, partitioned by METIS like @p previous, which it updates:
     * partition_like()), for the multiplier shared (every rank locates every
     * membrane point).
     */
    std::unique_ptr<parallel::TriangulationBase<3>>
    make_uptake_mesh(const UptakeMeshRecipe &recipe,
                     const DiffusionMethod   method,
                     const MPI_Comm          communicator,
                     TimerOutput            &timer,
                     Partition              &previous)
    {
      TimerOutput::Scope scope(timer, "diffusion mesh");
      if (method != DiffusionMethod::cut_cell)
        {
          auto mesh = std::make_unique<parallel::shared::Triangulation<3>>(
            communicator,
            Triangulation<3>::none,
            false,
            parallel::shared::Triangulation<3>::partition_metis);
          recipe.make(*mesh);
          return mesh;
        }
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(communicator);
      // Hanging nodes need the description's levels, which limit the level
      // difference at vertices to one.
      const auto description = TriangulationDescription::Utilities::
        create_description_from_triangulation_in_groups<3, 3>(
          [&recipe](Triangulation<3> &serial) { recipe.make(serial); },
          [n_ranks, &previous](Triangulation<3> &serial,
                               const MPI_Comm &,
                               const unsigned int) {
            partition_like(serial, n_ranks, previous);
          },
          communicator,
          n_ranks,
          Triangulation<3>::none,
          TriangulationDescription::Settings::construct_multigrid_hierarchy);
      auto mesh =
        std::make_unique<parallel::fullydistributed::Triangulation<3>>(
          communicator);
      create_capillary_mesh(*mesh, description);
      if (recipe.geometry.period())
        add_end_periodicity(*mesh);
      return mesh;
    }

    /// The vertices of @p mesh on all ranks: each counted by the lowest rank
    /// whose cells hold it.
    types::global_vertex_index
    n_global_vertices(const parallel::TriangulationBase<3> &mesh)
    {
      std::vector<types::subdomain_id> lowest(mesh.n_vertices(),
                                              numbers::invalid_subdomain_id);
      for (const auto &cell : mesh.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int v : cell->vertex_indices())
            lowest[cell->vertex_index(v)] =
              std::min(lowest[cell->vertex_index(v)], cell->subdomain_id());
      const types::subdomain_id  rank = mesh.locally_owned_subdomain();
      types::global_vertex_index n    = 0;
      for (const types::subdomain_id owner : lowest)
        n += (owner == rank);
      return Utilities::MPI::sum(n, mesh.get_communicator());
    }

    /// The CO diffusion problem of @p d, set up on @p mesh with the
    /// membranes @p surfaces: everything before the assembly. A mesh too
    /// coarse for the membranes is an InputError naming @p band_refinements,
    /// the refinements of the mesh around them. Cut cells ask for
    /// refinement where the distance has a ridge if @p refine_ridges.
    std::unique_ptr<DiffusionSolver>
    set_up_diffusion(const parallel::TriangulationBase<3>           &mesh,
                     const GeometryParameters                       &geometry,
                     const DiffusionParameters                      &d,
                     const std::vector<const Triangulation<2, 3> *> &surfaces,
                     const MappingQ<2, 3>                           &mapping,
                     const unsigned int                      band_refinements,
                     const bool                              refine_ridges,
                     std::shared_ptr<const MembraneDistance> distance,
                     const MPI_Comm                          communicator,
                     TimerOutput                            &timer)
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
          // The reaction's solve (solve_with_reaction()) comes on this mesh.
          cut_cells->separate_insides(d.uptake == CellUptake::reaction);
          cut_cells->share_membrane_distance(std::move(distance));
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
      {
        UptakeMeshRecipe recipe{
          geometry, mesh_parameters, surfaces, band_refinements, {}};
        Partition partition; // on the rank that builds the serial mesh
        mesh =
          make_uptake_mesh(recipe, d.method, communicator, timer, partition);
        // Cut cells: the membranes sampled once for every attempt below.
        if (d.method == DiffusionMethod::cut_cell)
          {
            TimerOutput::Scope scope(timer, "diffusion: membrane sampling");
            distance = std::make_shared<MembraneDistance>(surfaces,
                                                          mapping,
                                                          geometry.period());
          }
        // Cut cells: refine where two membranes share a mesh cell, or the
        // distance to them has a ridge in one, until none does; after the
        // last refinement allowed a shared cell is an error, a ridge is
        // left as the mesh resolves it.
        bool refine_ridges = true;
        for (;;)
          try
            {
              diffusion = set_up_diffusion(*mesh,
                                           geometry,
                                           d,
                                           surfaces,
                                           mapping,
                                           band_refinements,
                                           refine_ridges,
                                           distance,
                                           communicator,
                                           timer);
              return;
            }
          catch (const UnresolvedCutCells &e)
            {
              diffusion.reset();
              const unsigned int refinement = recipe.refinements.size();
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
              recipe.refinements.push_back(e.cells);
              mesh.reset();
              mesh = make_uptake_mesh(
                recipe, d.method, communicator, timer, partition);
            }
      }

      std::unique_ptr<parallel::TriangulationBase<3>> mesh;
      std::unique_ptr<DiffusionSolver>                diffusion;
      /// Cut cells: the distance to the membranes.
      std::shared_ptr<const MembraneDistance> distance;
    };

    /**
     * The finite-uptake problem of @p d with the binding rate @p rate
     * (CutCellDiffusion with a reaction inside the cells) on the mesh of
     * @p setup, assembled and solved.
     */
    std::unique_ptr<DiffusionSolver>
    solve_with_reaction(
      const UptakeSetup                              &setup,
      const GeometryParameters                       &geometry,
      const DiffusionParameters                      &d,
      const std::vector<const Triangulation<2, 3> *> &surfaces,
      const MappingQ<2, 3>                           &mapping,
      const double                                    rate,
      const MPI_Comm                                  communicator,
      TimerOutput                                    &timer)
    {
      auto reacting = std::make_unique<CutCellDiffusion>(
        d,
        [&d](const unsigned int id) { return d.permeability(id); },
        DiffusionBoundary::alveolar_surface,
        communicator,
        timer,
        geometry.period());
      // The mesh resolves the membranes already (the first solve's).
      reacting->refine_ridges(false);
      reacting->share_membrane_distance(setup.distance);
      reacting->react_inside_cells(d.cytoplasm_permeability(), rate);
      reacting->setup(*setup.mesh, surfaces, mapping);
      reacting->assemble();
      reacting->solve();
      return reacting;
    }
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

  namespace
  {
    /// The membrane sink's part of an Uptake: DM, and the mesh and the
    /// solve it took.
    Uptake
    sink_uptake(const UptakeSetup         &setup,
                const DiffusionParameters &d,
                const MPI_Comm             communicator)
    {
      const parallel::TriangulationBase<3> &mesh      = *setup.mesh;
      const DiffusionSolver                &diffusion = *setup.diffusion;
      Uptake                                uptake;
      uptake.dm_total = diffusion.dm_total();
      for (const double flow : diffusion.membrane_flows())
        uptake.dm_cells.push_back(flow / d.alveolar_pressure);
      uptake.n_nodes = n_global_vertices(mesh);
      uptake.n_cells = mesh.n_global_active_cells();
      uptake.n_cells_largest_rank =
        Utilities::MPI::max(mesh.n_active_cells(), communicator);
      uptake.n_dofs     = diffusion.n_dofs();
      uptake.iterations = diffusion.n_iterations();
      return uptake;
    }

    /// Add the DL of @p reacting to @p uptake.
    void
    add_dl(Uptake                    &uptake,
           const DiffusionSolver     &reacting,
           const DiffusionParameters &d)
    {
      uptake.dl_total      = reacting.dm_total();
      uptake.dl_iterations = reacting.n_iterations();
      uptake.dl_cells.clear();
      for (const double flow : reacting.membrane_flows())
        uptake.dl_cells.push_back(flow / d.alveolar_pressure);
    }
  } // namespace

  namespace
  {
    /**
     * What solve_uptake() and solve_uptake_for_rates() share: the sink's
     * solve on the uptake mesh, then with @p d's reaction one solve per
     * rate of @p rates, each Uptake's seconds the wall time since the one
     * before (the first's since the start); @p write_fields is given the
     * last solve.
     */
    std::vector<Uptake>
    solve_sink_and_rates(
      const GeometryParameters                           &geometry,
      const MeshParameters                               &mesh_parameters,
      const DiffusionParameters                          &d,
      const std::vector<const Triangulation<2, 3> *>     &surfaces,
      const MappingQ<2, 3>                               &mapping,
      const unsigned int                                  band_refinements,
      const std::vector<double>                          &rates,
      const MPI_Comm                                      communicator,
      TimerOutput                                        &timer,
      const std::function<void(const DiffusionSolver &)> &write_fields)
    {
      Timer             clock;
      const UptakeSetup setup(geometry,
                              mesh_parameters,
                              d,
                              surfaces,
                              mapping,
                              band_refinements,
                              communicator,
                              timer);
      setup.diffusion->assemble();
      setup.diffusion->solve();
      const Uptake sink = sink_uptake(setup, d, communicator);
      if (rates.empty())
        {
          if (write_fields)
            write_fields(*setup.diffusion);
          std::vector<Uptake> uptakes{sink};
          uptakes.back().seconds = clock.wall_time();
          return uptakes;
        }
      std::vector<Uptake> uptakes;
      for (const double rate : rates)
        {
          const std::unique_ptr<DiffusionSolver> reacting = solve_with_reaction(
            setup, geometry, d, surfaces, mapping, rate, communicator, timer);
          add_dl(uptakes.emplace_back(sink), *reacting, d);
          if (write_fields && uptakes.size() == rates.size())
            write_fields(*reacting);
          uptakes.back().seconds = clock.wall_time();
          clock.restart();
        }
      return uptakes;
    }
  } // namespace

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
    return solve_sink_and_rates(geometry,
                                mesh_parameters,
                                d,
                                surfaces,
                                mapping,
                                band_refinements,
                                d.uptake == CellUptake::reaction ?
                                  std::vector<double>{d.reaction_rate()} :
                                  std::vector<double>{},
                                communicator,
                                timer,
                                write_fields)
      .front();
  }

  std::vector<Uptake>
  solve_uptake_for_rates(
    const GeometryParameters                       &geometry,
    const MeshParameters                           &mesh_parameters,
    const DiffusionParameters                      &sink_parameters,
    const std::vector<const Triangulation<2, 3> *> &surfaces,
    const MappingQ<2, 3>                           &mapping,
    const unsigned int                              band_refinements,
    const std::vector<double>                      &rates,
    const MPI_Comm                                  communicator,
    TimerOutput                                    &timer)
  {
    if (sink_parameters.method != DiffusionMethod::cut_cell)
      throw InputError("Diffusion/Method",
                       "Lagrange multiplier",
                       "DL needs the cell interiors in the mesh: cut cell.");
    // The mesh the reaction needs (CutCellDiffusion::separate_insides()).
    DiffusionParameters d = sink_parameters;
    d.uptake              = CellUptake::reaction;
    return solve_sink_and_rates(geometry,
                                mesh_parameters,
                                d,
                                surfaces,
                                mapping,
                                band_refinements,
                                rates,
                                communicator,
                                timer,
                                {});
  }

  std::string
  dm_header(const unsigned int n_cells, const bool reaction)
  {
    std::string header = "time,dm_total";
    for (unsigned int c = 0; c < n_cells; ++c)
      header += ",dm_cell_" + std::to_string(c);
    if (reaction)
      {
        header += ",dl_total";
        for (unsigned int c = 0; c < n_cells; ++c)
          header += ",dl_cell_" + std::to_string(c);
      }
    return header;
  }

  std::string
  dm_row(const double time, const Uptake &uptake)
  {
    CsvRow row;
    row << time << uptake.dm_total;
    for (const double dm : uptake.dm_cells)
      row << dm;
    if (!uptake.dl_cells.empty())
      {
        row << uptake.dl_total;
        for (const double dl : uptake.dl_cells)
          row << dl;
      }
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

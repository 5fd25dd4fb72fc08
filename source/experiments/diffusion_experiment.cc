#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/experiments/diffusion_experiment.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_membranes.h>

#include <deal.II/distributed/shared_tria.h>

#include <cmath>
#include <iomanip>
#include <numeric>

namespace rbc_ifem
{
  DiffusionExperiment::DiffusionExperiment(const Parameters &parameters,
                                           const MPI_Comm    communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    // Rank 0's own clock (MPI_COMM_SELF): a TimerOutput on the world
    // communicator warns at length when an input error unwinds through it.
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
  {}

  void
  DiffusionExperiment::run(const ParameterHandler &prm)
  {
    pcout << "rbc-ifem: experiment '" << parameters.experiment << "' on "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)"
          << std::endl;
    if (parameters.experiment == "layouts")
      run_layouts();
    else if (parameters.experiment == "mesh convergence")
      run_mesh_convergence();
    else
      run_diffusion();

    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output_directory + "/parameters.prm",
                            [&](std::ostream &out) {
                              prm.print_parameters(out, ParameterHandler::PRM);
                            });
    write_timing(timer, parameters.output_directory, communicator);
    pcout << "  peak memory: " << peak_memory_mb(communicator)
          << " MB (largest over ranks)" << std::endl;
  }

  LayoutUptake
  solve_uptake(const Parameters                               &parameters,
               const std::vector<const Triangulation<2, 3> *> &surfaces,
               const MappingQ<2, 3>                           &mapping,
               const unsigned int                              band_refinements,
               const MPI_Comm                                  communicator,
               TimerOutput                                    &timer,
               const std::function<void(const CODiffusion &)> &write_fields)
  {
    Timer                              clock;
    parallel::shared::Triangulation<3> mesh(
      communicator,
      Triangulation<3>::none,
      false,
      parallel::shared::Triangulation<3>::partition_metis);
    {
      TimerOutput::Scope    scope(timer, "diffusion mesh");
      std::vector<Point<3>> band_points;
      for (const auto *surface : surfaces)
        band_points.insert(band_points.end(),
                           surface->get_vertices().begin(),
                           surface->get_vertices().end());
      create_diffusion_mesh(mesh,
                            parameters.geometry,
                            parameters.mesh.diffusion_global_refinements);
      refine_near_points(mesh,
                         band_points,
                         parameters.mesh.band_width,
                         band_refinements);
    }

    const DiffusionParameters &d = parameters.diffusion;
    CODiffusion                diffusion(
      d,
      [&d](const unsigned int id) { return d.permeability(id); },
      DiffusionBoundary::alveolar_surface,
      communicator,
      timer);
    diffusion.setup(mesh, surfaces, mapping);
    diffusion.assemble();
    diffusion.solve();
    if (write_fields)
      write_fields(diffusion);

    LayoutUptake uptake;
    uptake.dm_total = diffusion.dm_total();
    for (const double flow : diffusion.membrane_flows())
      uptake.dm_cells.push_back(flow / d.alveolar_pressure);
    uptake.n_nodes = mesh.n_used_vertices();
    uptake.n_cells = mesh.n_active_cells();
    uptake.n_dofs = diffusion.n_pressure_dofs() + diffusion.n_multiplier_dofs();
    uptake.iterations = diffusion.n_iterations();
    uptake.seconds    = clock.wall_time();
    return uptake;
  }

  LayoutUptake
  solve_layout(const Parameters       &parameters,
               const LayoutParameters &layout_parameters,
               const unsigned int      surface_refinements,
               const unsigned int      band_refinements,
               const MPI_Comm          communicator,
               TimerOutput            &timer,
               const std::string      &fields)
  {
    const CellLayout    layout(layout_parameters,
                            parameters.geometry,
                            parameters.cells);
    const CellMembranes membranes(
      layout.placements(),
      EvansFungShape::named(parameters.cells.shape, parameters.cells.diameter),
      surface_refinements);
    membranes.require_clearance(parameters.geometry.capillary_radius);

    const std::string &directory = parameters.output_directory;
    const auto         write     = [&](const CODiffusion &diffusion) {
      create_output_directory(directory, communicator);
      const CODiffusion::OutputFiles files =
        diffusion.write_output(directory, fields);
      write_pvd(directory, fields, {{0., files.pressure}}, communicator);
      write_pvd(directory,
                fields + "_membranes",
                {{0., files.membranes}},
                communicator);
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        write_file_atomically(directory + "/cells.csv", [&](std::ostream &out) {
          membranes.write_table(out);
        });
    };
    LayoutUptake uptake =
      solve_uptake(parameters,
                   membranes.surfaces(),
                   membranes.mapping(),
                   band_refinements,
                   communicator,
                   timer,
                   fields.empty() ? std::function<void(const CODiffusion &)>() :
                                    write);
    uptake.hematocrit = layout.hematocrit(membranes.volumes());
    return uptake;
  }

  void
  DiffusionExperiment::report(const std::string  &what,
                              const LayoutUptake &uptake) const
  {
    pcout << "  " << what << ": " << uptake.n_dofs << " DoFs, "
          << uptake.iterations << " FGMRES iterations, " << std::setprecision(4)
          << uptake.seconds << " s; DM " << std::setprecision(6)
          << uptake.dm_total << " µm³/(s Torr)" << std::endl;
  }

  void
  DiffusionExperiment::run_diffusion()
  {
    const LayoutUptake uptake =
      solve_layout(parameters,
                   parameters.layout,
                   parameters.cells.surface_refinements,
                   parameters.mesh.diffusion_band_refinements,
                   communicator,
                   timer,
                   "diffusion");
    report(parameters.layout.kind + ", " +
             std::to_string(uptake.dm_cells.size()) + " cells",
           uptake);
    for (unsigned int c = 0; c < uptake.dm_cells.size(); ++c)
      pcout << "    cell " << c << ": DM " << uptake.dm_cells[c] << std::endl;

    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(
        parameters.output_directory + "/dm.csv", [&](std::ostream &out) {
          out << "time,dm_total";
          for (unsigned int c = 0; c < uptake.dm_cells.size(); ++c)
            out << ",dm_cell_" << c;
          out << '\n' << std::setprecision(10) << 0. << ',' << uptake.dm_total;
          for (const double dm : uptake.dm_cells)
            out << ',' << dm;
          out << '\n';
        });
    pcout
      << "  wrote " << parameters.output_directory
      << "/: dm.csv, cells.csv, diffusion.pvd (P), diffusion_membranes.pvd (flux), "
         "parameters.prm, timing.csv"
      << std::endl;
  }

  std::vector<std::vector<LayoutParameters>>
  DiffusionExperiment::study_layouts() const
  {
    const LayoutStudyParameters               &study = parameters.layout_study;
    std::vector<std::vector<LayoutParameters>> layouts;
    for (const std::string &kind : study.kinds)
      for (const unsigned int n : study.numbers_of_cells)
        {
          layouts.emplace_back();
          const unsigned int n_samples = kind == "random" ? study.n_seeds : 1;
          for (unsigned int sample = 0; sample < n_samples; ++sample)
            {
              LayoutParameters layout = parameters.layout;
              layout.kind             = kind;
              layout.n_cells          = n;
              layout.seed             = parameters.layout.seed + sample;
              try
                {
                  CellLayout(layout, parameters.geometry, parameters.cells);
                }
              catch (const InputError &e)
                {
                  throw InputError("Layout study/Numbers of cells",
                                   std::to_string(n),
                                   std::string("the " + kind +
                                               " layout of that many cells "
                                               "is impossible: ") +
                                     e.what());
                }
              layouts.back().push_back(layout);
            }
        }
    return layouts;
  }

  void
  DiffusionExperiment::run_layouts()
  {
    const auto layouts = study_layouts();

    std::ostringstream table;
    table
      << "layout,n_cells,hematocrit,dm_total,dm_per_cell,dm_total_std,n_samples\n"
      << std::setprecision(10);
    for (const auto &samples : layouts)
      {
        std::vector<double> dm;
        double              hematocrit = 0.;
        for (const LayoutParameters &layout : samples)
          {
            const LayoutUptake uptake =
              solve_layout(parameters,
                           layout,
                           parameters.cells.surface_refinements,
                           parameters.mesh.diffusion_band_refinements,
                           communicator,
                           timer);
            report(layout.kind + ", " + std::to_string(layout.n_cells) +
                     " cells, seed " + std::to_string(layout.seed),
                   uptake);
            dm.push_back(uptake.dm_total);
            hematocrit += uptake.hematocrit / samples.size();
          }
        const double mean =
          std::accumulate(dm.begin(), dm.end(), 0.) / dm.size();
        double variance = 0.;
        for (const double x : dm)
          variance +=
            (x - mean) * (x - mean) / std::max<std::size_t>(1, dm.size() - 1);
        const unsigned int n = samples.front().n_cells;
        table << samples.front().kind << ',' << n << ',' << hematocrit << ','
              << mean << ',' << mean / n << ',' << std::sqrt(variance) << ','
              << dm.size() << '\n';
      }
    create_output_directory(parameters.output_directory, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output_directory + "/layouts.csv",
                            [&](std::ostream &out) { out << table.str(); });
    pcout << "  wrote " << parameters.output_directory
          << "/: layouts.csv, parameters.prm, timing.csv" << std::endl;
  }

  void
  DiffusionExperiment::run_mesh_convergence()
  {
    std::vector<LayoutUptake> levels;
    for (unsigned int level = 0; level < parameters.mesh_convergence.n_levels;
         ++level)
      {
        levels.push_back(
          solve_layout(parameters,
                       parameters.layout,
                       parameters.cells.surface_refinements + level,
                       parameters.mesh.diffusion_band_refinements + level,
                       communicator,
                       timer));
        report("level " + std::to_string(level) + ", " +
                 std::to_string(levels.back().n_nodes) + " nodes",
               levels.back());
      }

    // Richardson extrapolation from the last three levels (h halves from
    // level to level): DM(h) = DM* + C h^p.
    const unsigned int L  = levels.size() - 1;
    const double       d2 = levels[L].dm_total, d1 = levels[L - 1].dm_total;
    const double       ratio =
      L >= 2 ? (d1 - levels[L - 2].dm_total) / (d2 - d1) : 0.;
    const bool   monotone = ratio > 1.;
    const double limit    = monotone ? d2 + (d2 - d1) / (ratio - 1.) : d2;
    if (monotone)
      pcout << "  extrapolated DM " << limit << " µm³/(s Torr), observed order "
            << std::log2(ratio) << std::endl;
    else
      pcout
        << "  the last levels do not converge monotonically; differences are "
           "taken from the finest level"
        << std::endl;

    create_output_directory(parameters.output_directory, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(
        parameters.output_directory + "/convergence.csv",
        [&](std::ostream &out) {
          out << "level,n_nodes,n_cells,n_dofs,dm_total,relative_change,"
                 "surface_refinements,band_refinements,iterations,"
                 "seconds,difference_from_limit\n"
              << std::setprecision(10);
          for (unsigned int l = 0; l <= L; ++l)
            {
              const LayoutUptake &u = levels[l];
              out << l << ',' << u.n_nodes << ',' << u.n_cells << ','
                  << u.n_dofs << ',' << u.dm_total << ',';
              if (l == 0)
                out << "nan";
              else
                out << std::abs(u.dm_total - levels[l - 1].dm_total) /
                         u.dm_total;
              out << ',' << parameters.cells.surface_refinements + l << ','
                  << parameters.mesh.diffusion_band_refinements + l << ','
                  << u.iterations << ',' << u.seconds << ','
                  << std::abs(u.dm_total - limit) / limit << '\n';
            }
        });
    pcout << "  wrote " << parameters.output_directory
          << "/: convergence.csv, parameters.prm, timing.csv" << std::endl;
  }
} // namespace rbc_ifem

#include <rbc_ifem/capillary_mesh.h>
#include <rbc_ifem/geometry_experiment.h>
#include <rbc_ifem/input_error.h>
#include <rbc_ifem/output.h>

#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  GeometryExperiment::GeometryExperiment(const Parameters &parameters,
                                         const MPI_Comm    communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
    , layout(parameters.layout, parameters.geometry, parameters.cells)
    , membrane_mapping(2)
    , fluid_mesh(communicator,
                 Triangulation<3>::none,
                 false,
                 parallel::shared::Triangulation<3>::partition_metis)
    , diffusion_mesh(communicator,
                     Triangulation<3>::none,
                     false,
                     parallel::shared::Triangulation<3>::partition_metis)
  {}

  void
  GeometryExperiment::run(const ParameterHandler &prm)
  {
    pcout << "rbc-ifem: experiment 'geometry' on "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)\n"
          << "  layout: " << parameters.layout.kind << ", "
          << layout.placements().size() << " of at most " << layout.max_cells()
          << " cells, cell length along the axis " << layout.cell_length()
          << " µm" << std::endl;

    create_membranes();
    check_clearance();
    create_meshes();
    write_output(prm);
    write_timing(timer, parameters.output_directory, communicator);

    pcout << "  peak memory: " << peak_memory_mb(communicator)
          << " MB (largest over ranks)" << std::endl;
  }

  void
  GeometryExperiment::create_membranes()
  {
    TimerOutput::Scope   scope(timer, "membranes");
    const EvansFungShape shape(parameters.cells.diameter);
    std::vector<double>  volumes;
    for (const CellPlacement &placement : layout.placements())
      {
        membranes.push_back(std::make_unique<Triangulation<2, 3>>());
        create_cell_surface(*membranes.back(),
                            shape,
                            placement,
                            parameters.cells.surface_refinements);
        measures.push_back(measure_surface(*membranes.back(), membrane_mapping));
        volumes.push_back(measures.back().volume);
      }
    pcout << "  membranes: " << membranes.size() << " x "
          << (membranes.empty() ? 0 : membranes[0]->n_active_cells())
          << " quadrilaterals; tube hematocrit " << layout.hematocrit(volumes)
          << std::endl;
  }

  void
  GeometryExperiment::check_clearance() const
  {
    TimerOutput::Scope scope(timer, "clearance check");
    const Clearance    clearance = measure_clearance(membrane_pointers(),
                                                  membrane_mapping,
                                                  parameters.geometry.capillary_radius);
    pcout << "  clearance: nearest membranes " << clearance.min_cell_gap
          << " µm apart";
    if (membranes.size() > 1)
      pcout << " (cells " << clearance.closest_cells.first << " and "
            << clearance.closest_cells.second << ')';
    pcout << ", nearest wall " << clearance.min_wall_gap << " µm away" << std::endl;

    // The layout keeps the true surfaces apart; meshes too coarse to follow
    // them can still cross, which no solver would survive.
    if (clearance.min_cell_gap <= 0. || clearance.min_wall_gap <= 0.)
      throw InputError("Cells/Surface refinements",
                       std::to_string(parameters.cells.surface_refinements),
                       "the meshed membranes of this layout cross each other "
                       "or the wall; refine them or widen Layout/Minimum gap.");
  }

  void
  GeometryExperiment::create_meshes()
  {
    const std::vector<Point<3>> points = membrane_points();
    {
      TimerOutput::Scope scope(timer, "fluid mesh");
      create_fluid_mesh(fluid_mesh,
                        parameters.geometry,
                        parameters.mesh.fluid_global_refinements);
      refine_near_points(fluid_mesh,
                         points,
                         parameters.mesh.band_width,
                         parameters.mesh.fluid_band_refinements);
    }
    {
      TimerOutput::Scope scope(timer, "diffusion mesh");
      create_diffusion_mesh(diffusion_mesh,
                            parameters.geometry,
                            parameters.mesh.diffusion_global_refinements);
      refine_near_points(diffusion_mesh,
                         points,
                         parameters.mesh.band_width,
                         parameters.mesh.diffusion_band_refinements);
    }
    pcout << "  fluid mesh: " << fluid_mesh.n_active_cells()
          << " cells, diffusion mesh: " << diffusion_mesh.n_active_cells()
          << " cells" << std::endl;
  }

  void
  GeometryExperiment::write_output(const ParameterHandler &prm) const
  {
    TimerOutput::Scope scope(timer, "output");
    const std::string &directory = parameters.output_directory;
    create_output_directory(directory, communicator);

    write_volume_mesh(fluid_mesh, directory, "fluid_mesh", communicator);
    write_volume_mesh(diffusion_mesh, directory, "diffusion_mesh", communicator);
    write_membranes(membrane_pointers(), membrane_mapping, directory, "membranes", communicator);

    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        write_file_atomically(directory + "/parameters.prm", [&](std::ostream &out) {
          prm.print_parameters(out, ParameterHandler::PRM);
        });
        write_file_atomically(directory + "/cells.csv", [&](std::ostream &out) {
          out << "cell,x,y,z,area,volume\n" << std::setprecision(10);
          for (unsigned int i = 0; i < measures.size(); ++i)
            out << i << ',' << measures[i].centroid[0] << ','
                << measures[i].centroid[1] << ',' << measures[i].centroid[2]
                << ',' << measures[i].area << ',' << measures[i].volume << '\n';
        });
      }
    pcout << "  wrote " << directory << "/: parameters.prm, cells.csv, "
          << "fluid_mesh.pvd, diffusion_mesh.pvd (+ _boundary), membranes.pvd, "
          << "timing.csv" << std::endl;
  }

  std::vector<Point<3>>
  GeometryExperiment::membrane_points() const
  {
    std::vector<Point<3>> points;
    for (const auto &membrane : membranes)
      points.insert(points.end(),
                    membrane->get_vertices().begin(),
                    membrane->get_vertices().end());
    return points;
  }

  std::vector<const Triangulation<2, 3> *>
  GeometryExperiment::membrane_pointers() const
  {
    std::vector<const Triangulation<2, 3> *> pointers;
    for (const auto &membrane : membranes)
      pointers.push_back(membrane.get());
    return pointers;
  }
} // namespace rbc_ifem

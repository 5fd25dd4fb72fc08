#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/experiments/geometry_experiment.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

namespace rbc_ifem
{
  GeometryExperiment::GeometryExperiment(const ExperimentContext &context)
    : Experiment(context, ParametersFile::after_work)
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
  GeometryExperiment::setup()
  {
    layout = std::make_unique<const CellLayout>(parameters.layout,
                                                parameters.geometry,
                                                parameters.cells);
    {
      TimerOutput::Scope scope(timer, "membranes");
      membranes = std::make_unique<const CellMembranes>(
        layout->placements(),
        EvansFungShape::of(parameters.cells),
        parameters.cells.surface_refinements);
    }
    pcout << "  layout: "
          << name_of(parameters.layout.kind, layout_kind_names()) << ", "
          << layout->placements().size() << " of at most "
          << layout->max_cells() << " cells, cell length along the axis "
          << layout->cell_length() << " µm" << std::endl;
    report_membranes();
    create_meshes();
  }

  void
  GeometryExperiment::report_membranes()
  {
    TimerOutput::Scope scope(timer, "clearance check");
    pcout << "  membranes: " << membranes->size() << " x "
          << (membranes->size() == 0 ?
                0 :
                membranes->surfaces()[0]->n_active_cells())
          << " quadrilaterals; tube hematocrit "
          << layout->hematocrit(membranes->volumes()) << std::endl;
    const Clearance clearance =
      membranes->require_clearance(parameters.geometry.capillary_radius);
    pcout << "  clearance: nearest membranes " << clearance.min_cell_gap
          << " µm apart";
    if (membranes->size() > 1)
      pcout << " (cells " << clearance.closest_cells.first << " and "
            << clearance.closest_cells.second << ')';
    pcout << ", nearest wall " << clearance.min_wall_gap << " µm away"
          << std::endl;
  }

  void
  GeometryExperiment::create_meshes()
  {
    const std::vector<Point<3>> points = membranes->vertices();
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
  GeometryExperiment::execute()
  {
    TimerOutput::Scope scope(timer, "output");
    const std::string &directory = parameters.output_directory;
    create_output_directory(directory, communicator);
    write_together(communicator, [&]() {
      write_volume_mesh(fluid_mesh, directory, "fluid_mesh", communicator);
      write_volume_mesh(diffusion_mesh,
                        directory,
                        "diffusion_mesh",
                        communicator);
      const std::string membrane_file = write_membranes(membranes->surfaces(),
                                                        membranes->mapping(),
                                                        directory,
                                                        "membranes",
                                                        communicator);
      write_pvd(directory, "membranes", {{0., membrane_file}}, communicator);
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        membranes->table().write(directory + "/cells.csv");
    });
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/experiments/diffusion_experiment.h>

namespace rbc_ifem
{
  void
  DiffusionExperiment::setup()
  {
    cells =
      std::make_unique<const PlacedCells>(parameters.layout,
                                          parameters.geometry,
                                          parameters.cells,
                                          parameters.cells.surface_refinements);
  }

  void
  DiffusionExperiment::execute()
  {
    const std::string &directory    = parameters.output_directory;
    const auto         write_fields = [&](const DiffusionSolver &diffusion) {
      create_output_directory(directory, communicator);
      UptakeFields().write(diffusion, directory, 0., 0, communicator);
    };
    const Uptake uptake = solve(*cells, write_fields);
    report(name_of(parameters.layout.kind, layout_kind_names()) + ", " +
             std::to_string(uptake.dm_cells.size()) + " cells",
           uptake);
    for (unsigned int c = 0; c < uptake.dm_cells.size(); ++c)
      pcout << "    cell " << c << ": DM " << uptake.dm_cells[c] << std::endl;

    write_on_rank_0(communicator, [&]() {
      cells->membranes.table().write(directory + "/cells.csv");
      CsvTable dm(dm_header(uptake.dm_cells.size(), !uptake.dl_cells.empty()));
      dm.add_row(dm_row(0., uptake));
      dm.write(directory + "/dm.csv");
    });
  }
} // namespace rbc_ifem

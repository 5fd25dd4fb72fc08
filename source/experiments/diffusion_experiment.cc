#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/experiments/diffusion_experiment.h>

namespace rbc_ifem
{
  void
  DiffusionExperiment::setup()
  {
    cells =
      std::make_unique<const PlacedCells>(parameters,
                                          parameters.cells.surface_refinements);
  }

  void
  DiffusionExperiment::execute()
  {
    const std::string &directory    = parameters.output_directory;
    const auto         write_fields = [&](const CODiffusion &diffusion) {
      const CODiffusion::OutputFiles files =
        diffusion.write_output(directory, "diffusion");
      write_pvd(directory, "diffusion", {{0., files.pressure}}, communicator);
      write_pvd(directory,
                "diffusion_membranes",
                {{0., files.membranes}},
                communicator);
    };
    const Uptake uptake =
      solve(*cells, parameters.mesh.diffusion_band_refinements, write_fields);
    report(name_of(parameters.layout.kind, layout_kind_names()) + ", " +
             std::to_string(uptake.dm_cells.size()) + " cells",
           uptake);
    for (unsigned int c = 0; c < uptake.dm_cells.size(); ++c)
      pcout << "    cell " << c << ": DM " << uptake.dm_cells[c] << std::endl;

    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        cells->membranes.table().write(directory + "/cells.csv");
        std::string header = "time,dm_total";
        CsvRow      row;
        row << 0. << uptake.dm_total;
        for (unsigned int c = 0; c < uptake.dm_cells.size(); ++c)
          {
            header += ",dm_cell_" + std::to_string(c);
            row << uptake.dm_cells[c];
          }
        CsvTable dm(header);
        dm.add_row(row.str());
        dm.write(directory + "/dm.csv");
      }
  }
} // namespace rbc_ifem

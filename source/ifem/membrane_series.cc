#include <rbc_ifem/base/output.h>
#include <rbc_ifem/ifem/membrane_series.h>

namespace rbc_ifem
{
  namespace
  {
    /// Every cell's file and its series, by the cell's writer.
    void
    write_per_cell(const CellPopulation &cells,
                   RunRecord            &record,
                   const std::string    &directory,
                   const FieldData      &field_data,
                   const MPI_Comm        communicator)
    {
      // Every rank keeps every cell's list, which a checkpoint holds.
      const std::vector<std::string> files = cells.write_vtu(
        directory, "cell", record.step, field_data, communicator);
      for (unsigned int c = 0; c < cells.size(); ++c)
        {
          record.cell_files[c].emplace_back(record.time, files[c]);
          write_pvd(directory,
                    "cell_" + std::to_string(c),
                    record.cell_files[c],
                    communicator,
                    cells.writer(c, communicator));
        }
    }

    /// The grouped file and its series, the fluid's records renamed.
    void
    write_grouped(const CellPopulation &cells,
                  const RunRecord      &record,
                  const std::string    &directory,
                  const FieldData      &field_data,
                  const MPI_Comm        communicator)
    {
      const std::string stem = "membranes";
      cells.write_grouped_vtu(
        directory, stem, record.step, field_data, communicator);
      std::vector<std::pair<double, std::string>> records;
      for (const auto &[time, fluid_file] : record.fluid_files)
        {
          Assert(fluid_file.rfind("flow_", 0) == 0,
                 ExcMessage("The fluid's files are named flow_SSSS."));
          records.emplace_back(time, stem + fluid_file.substr(4));
        }
      write_pvd(directory,
                stem,
                records,
                communicator,
                cells.writers(communicator).front());
    }
  } // namespace

  void
  write_membrane_series(const CellPopulation &cells,
                        const MembraneFiles   files,
                        RunRecord            &record,
                        const std::string    &directory,
                        const FieldData      &field_data,
                        const MPI_Comm        communicator)
  {
    if (files == MembraneFiles::grouped)
      write_grouped(cells, record, directory, field_data, communicator);
    else
      write_per_cell(cells, record, directory, field_data, communicator);
  }
} // namespace rbc_ifem

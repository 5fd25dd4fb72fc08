#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/diffusion/diffusion_solver.h>
#include <rbc_ifem/diffusion/uptake.h>

namespace rbc_ifem
{
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

  UptakeFields::UptakeFields(const std::string &name)
    : name(name)
  {}

  void
  UptakeFields::write(const DiffusionSolver &diffusion,
                      const std::string     &directory,
                      const double           time,
                      const unsigned int     counter,
                      const MPI_Comm         communicator,
                      const FieldData       &field_data)
  {
    // write_output() does what the ranks do together before it writes.
    write_together(communicator, [&]() {
      const DiffusionSolver::OutputFiles files =
        diffusion.write_output(directory, name, counter, field_data);
      pressure.emplace_back(time, files.pressure);
      membranes.emplace_back(time, files.membranes);
      write_pvd(directory, name, pressure, communicator);
      write_pvd(directory, name + "_membranes", membranes, communicator);
    });
  }
} // namespace rbc_ifem

/* ---------------------------------------------------------------------
 * rbc-ifem tutorial step-4: your own readout.
 *
 * step-3 wrote the immersed method's loop out; for real runs the library's
 * IFEMSimulation runs it, with everything around it: the frame, the
 * divergence guards, the fields for ParaView, the tables, checkpoints.
 * What a study wants to know beyond those tables it records with an
 * observer, a RunObserver it hands the simulation. This one asks how well
 * each square micrometre of membrane takes up CO as the cell deforms: the
 * DM per membrane area, DM_c / A_c, at every DM instant.
 * examples/step-4/README.md is this program's page.
 * --------------------------------------------------------------------- */

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/ifem_simulation.h>
#include <rbc_ifem/ifem/run_observer.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <iostream>
#include <sstream>
#include <utility>

using namespace dealii;
using namespace rbc_ifem;

// @sect3{The observer}
//
// IFEMSimulation calls record_uptake() after every DM solve, with DM per
// cell, and record() at the start and at every output step, with the
// cells' shapes (at the start the shapes come first, later the uptake).
// Whichever of the two arrives second completes the row of that instant.
// progress() adds words to the simulation's progress line, write_tables()
// writes the observer's table whenever the simulation writes its own.
class UptakePerArea : public RunObserver
{
public:
  UptakePerArea()
    : table("time,cell,area,dm,dm_per_area")
  {}

  void
  record_uptake(const double  time,
                const Uptake &uptake,
                const double /*smallest_gap*/) override
  {
    dm_time  = time;
    dm_cells = uptake.dm_cells;
    add_row();
  }

  void
  record(const double time, const std::vector<CellShape> &shapes) override
  {
    shape_time = time;
    areas.clear();
    for (const CellShape &shape : shapes)
      areas.push_back(shape.area);
    add_row();
  }

  std::string
  progress(const std::vector<CellShape> &) const override
  {
    std::ostringstream words;
    words << ", DM per area " << last_per_area << " µm/(s Torr)";
    return words.str();
  }

  void
  write_tables(const std::string &directory) const override
  {
    table.write(directory + "/uptake_per_area.csv");
  }

  /// DM per area of cell 0 at the first and the last DM instant.
  std::pair<double, double>
  first_and_last() const
  {
    return {first_per_area, last_per_area};
  }

private:
  /// The row of an instant that has both its DM and its shapes.
  void
  add_row()
  {
    if (dm_time != shape_time || dm_time == row_time)
      return;
    for (unsigned int c = 0; c < areas.size(); ++c)
      table.add(dm_time, c, areas[c], dm_cells[c], dm_cells[c] / areas[c]);
    last_per_area = dm_cells[0] / areas[0];
    if (row_time < 0.)
      first_per_area = last_per_area;
    row_time = dm_time;
  }

  CsvTable            table;
  double              dm_time = -1., shape_time = -2., row_time = -3.;
  std::vector<double> dm_cells, areas;
  double              first_per_area = 0., last_per_area = 0.;
};

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   communicator = MPI_COMM_WORLD;

  Parameters       parameters;
  ParameterHandler prm;
  parameters.add_parameters(prm);
  prm.parse_input(argc > 1 ? argv[1] : "step-4.prm");
  parameters.validate();

  // @sect3{The run}
  //
  // The simulation of the cells of subsection Layout in the capillary,
  // with the observer installed: setup() builds everything and rejects bad
  // input before anything is written; then the output directory with the
  // run's parameters.prm, and run() does the time loop.
  TimerOutput       timer(MPI_COMM_SELF,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  UptakePerArea     observer;
  const std::string text = parameter_text(prm);
  IFEMSimulation    simulation(
    parameters, text, FlowDomain::capillary(parameters), communicator, timer);
  simulation.add_observer(observer);
  simulation.setup();
  write_parameters(text, parameters.output_directory, communicator);
  simulation.run();

  const auto [first, last] = observer.first_and_last();
  if (Utilities::MPI::this_mpi_process(communicator) == 0)
    std::cout << "DM per membrane area of cell 0: " << first << " at t = 0, "
              << last << " at the end [µm/(s Torr)], " << std::showpos
              << 100. * (last / first - 1.) << std::noshowpos << "%"
              << std::endl;
}

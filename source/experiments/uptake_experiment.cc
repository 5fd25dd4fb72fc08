#include <rbc_ifem/experiments/uptake_experiment.h>

#include <iomanip>

namespace rbc_ifem
{
  UptakeExperiment::UptakeExperiment(const std::string      &name,
                                     const Parameters       &parameters,
                                     const ParameterHandler &prm,
                                     const MPI_Comm          communicator)
    : Experiment(name,
                 parameters,
                 prm,
                 communicator,
                 ParametersFile::after_work)
  {}

  Uptake
  UptakeExperiment::solve(
    const PlacedCells                                  &cells,
    const unsigned int                                  band_refinements,
    const std::function<void(const DiffusionSolver &)> &write_fields)
  {
    return solve_uptake(parameters.geometry,
                        parameters.mesh,
                        parameters.diffusion,
                        cells.membranes.surfaces(),
                        cells.membranes.mapping(),
                        band_refinements,
                        communicator,
                        timer,
                        write_fields);
  }

  void
  UptakeExperiment::report(const std::string &what, const Uptake &uptake)
  {
    pcout << "  " << what << ": " << uptake.n_dofs << " DoFs, "
          << uptake.iterations << " solver iterations, " << std::setprecision(4)
          << uptake.seconds << " s; DM " << std::setprecision(6)
          << uptake.dm_total << " µm³/(s Torr)";
    if (!uptake.dl_cells.empty())
      pcout << ", DL " << uptake.dl_total << " µm³/(s Torr)";
    pcout << std::endl
          << "    diffusion mesh: " << uptake.n_cells << " cells, "
          << uptake.n_cells_largest_rank << " on the largest rank" << std::endl;
  }
} // namespace rbc_ifem

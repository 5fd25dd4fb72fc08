#include <rbc_ifem/experiments/uptake_experiment.h>

#include <iomanip>

namespace rbc_ifem
{
  UptakeExperiment::UptakeExperiment(const ExperimentContext &context)
    : Experiment(context, ParametersFile::after_work)
    , uptake(uptake_solver(parameters.mesh.diffusion_band_refinements))
  {}

  UptakeSolver
  UptakeExperiment::uptake_solver(const unsigned int band_refinements)
  {
    MeshParameters mesh             = parameters.mesh;
    mesh.diffusion_band_refinements = band_refinements;
    return UptakeSolver(
      parameters.geometry, mesh, parameters.diffusion, communicator, timer);
  }

  Uptake
  UptakeExperiment::solve(
    const PlacedCells                                  &cells,
    const std::function<void(const DiffusionSolver &)> &write_fields)
  {
    return uptake.solve(cells.membranes.membrane_surfaces(), write_fields);
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

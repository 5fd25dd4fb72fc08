#ifndef rbc_ifem_experiments_uptake_experiment_h
#define rbc_ifem_experiments_uptake_experiment_h

#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/geometry/placed_cells.h>

#include <functional>
#include <string>

namespace rbc_ifem
{
  /**
   * What the CO uptake experiments (diffusion, layouts, finite uptake, mesh
   * convergence) share: each is a steady diffusion solve (UptakeSolver) per
   * layout on the capillary's diffusion mesh, refined in a band around the
   * membranes, and a progress line per solve.
   */
  class UptakeExperiment : public Experiment
  {
  public:
    /// Its files all come from finished solves: ParametersFile::after_work.
    explicit UptakeExperiment(const ExperimentContext &context);

  protected:
    /**
     * The uptake solver of the run's parameters, with Mesh/Diffusion band
     * refinements = @p band_refinements (a mesh convergence study's level).
     */
    UptakeSolver
    uptake_solver(const unsigned int band_refinements);

    /// The uptake of @p cells by the run's solver; @p write_fields as for
    /// UptakeSolver::solve().
    Uptake
    solve(
      const PlacedCells                                  &cells,
      const std::function<void(const DiffusionSolver &)> &write_fields = {});

    /// The progress line of one solve.
    void
    report(const std::string &what, const Uptake &uptake);

    /// The run's uptake solver (Mesh/Diffusion band refinements as given).
    const UptakeSolver uptake;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_experiments_uptake_experiment_h
#define rbc_ifem_experiments_uptake_experiment_h

#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/geometry/placed_cells.h>

#include <functional>
#include <string>

namespace rbc_ifem
{
  /**
   * What the CO uptake experiments (diffusion, layouts, mesh convergence)
   * share: each is a steady diffusion solve (DiffusionSolver, through
   * solve_uptake()) per layout on the capillary's diffusion mesh, refined in
   * a band around the membranes, and a progress line per solve.
   */
  class UptakeExperiment : public Experiment
  {
  public:
    /// Its files all come from finished solves: ParametersFile::after_work.
    UptakeExperiment(const std::string      &name,
                     const Parameters       &parameters,
                     const ParameterHandler &prm,
                     const MPI_Comm          communicator);

  protected:
    /**
     * The uptake of @p cells on the diffusion mesh refined
     * @p band_refinements times around them; @p write_fields as for
     * solve_uptake().
     */
    Uptake
    solve(
      const PlacedCells                                  &cells,
      const unsigned int                                  band_refinements,
      const std::function<void(const DiffusionSolver &)> &write_fields = {});

    /// The progress line of one solve.
    void
    report(const std::string &what, const Uptake &uptake);
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_experiments_diffusion_experiment_h
#define rbc_ifem_experiments_diffusion_experiment_h

#include <rbc_ifem/experiments/uptake_experiment.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * Experiment "diffusion": the steady CO uptake of the layout of subsection
   * Layout. Writes dm.csv (one row, time 0), cells.csv, the P field and the
   * membrane flux map (diffusion.pvd, diffusion_membranes.pvd), all after
   * the solve has succeeded.
   */
  class DiffusionExperiment : public UptakeExperiment
  {
  public:
    using UptakeExperiment::UptakeExperiment;

  private:
    /// The layout and its membranes, checked.
    void
    setup() override;
    void
    execute() override;

    std::unique_ptr<const PlacedCells> cells;
  };
} // namespace rbc_ifem

#endif

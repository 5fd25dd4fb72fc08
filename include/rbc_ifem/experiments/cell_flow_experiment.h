#ifndef rbc_ifem_experiments_cell_flow_experiment_h
#define rbc_ifem_experiments_cell_flow_experiment_h

#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/ifem/ifem_simulation.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * Experiment "flow" with Immersed cells/Enabled: the red cells of
   * subsection Layout carried by the plasma through the capillary, the
   * immersed method of IFEMSimulation, with DM on the deforming cells every
   * Immersed cells/Diffusion interval steps. The default experiment, one
   * cell becoming a parachute (prm/default.prm), is one. Writes flow.csv,
   * cells.csv, dm.csv, the fluid and membrane fields and, with Checkpoint
   * interval, checkpoint.bin.
   */
  class CellFlowExperiment : public Experiment
  {
  public:
    explicit CellFlowExperiment(const ExperimentContext &context);

  private:
    /// The cells in the capillary (InputError if there are none), the
    /// meshes, the operators (and the checkpoint with Resume).
    void
    setup() override;
    /// The time loop.
    void
    execute() override;

    std::unique_ptr<IFEMSimulation> simulation;
  };
} // namespace rbc_ifem

#endif

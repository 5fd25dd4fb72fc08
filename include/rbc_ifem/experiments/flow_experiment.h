#ifndef rbc_ifem_experiments_flow_experiment_h
#define rbc_ifem_experiments_flow_experiment_h

#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/fluid/fluid_problem.h>

#include <deal.II/distributed/fully_distributed_tria.h>

namespace rbc_ifem
{
  /**
   * Experiment "flow" without cells: the plasma alone in the capillary, for
   * Time/Number of steps steps of Δt from rest. flow.csv gets a row every
   * step (time,flow_rate,pressure_drop,max_velocity,divergence_l2, then
   * frame_velocity,newton_iterations,linear_iterations,lab_flow_rate: the
   * flow rate in the moving frame and in the laboratory's) and is written with
   * v and p (VTU/PVTU, flow.pvd) every Time/Output interval steps, at the
   * end, and up to the last good step if the solver fails; a progress line
   * per step.
   */
  class FlowExperiment : public Experiment
  {
  public:
    explicit FlowExperiment(const ExperimentContext &context);

  private:
    /// The mesh and the fluid's operators.
    void
    setup() override;
    /// The time steps.
    void
    execute() override;

    parallel::fullydistributed::Triangulation<3> triangulation;
    FluidProblem                                 fluid;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_flow_experiment_h
#define rbc_ifem_flow_experiment_h

#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>

namespace rbc_ifem
{
  /**
   * Experiment "flow": the plasma alone (no cells) in the capillary, for
   * Time/Number of steps steps of Δt from rest. Writes flow.csv every step
   * (time,flow_rate,pressure_drop,max_velocity,divergence_l2, then
   * frame_velocity,newton_iterations,linear_iterations), v and p as
   * VTU/PVTU with flow.pvd every Time/Output interval steps, timing.csv and
   * parameters.prm, and a progress line per step.
   */
  class FlowExperiment
  {
  public:
    FlowExperiment(const Parameters &parameters, const MPI_Comm communicator);

    void
    run(const ParameterHandler &prm);

  private:
    const Parameters                   parameters;
    const MPI_Comm                     communicator;
    ConditionalOStream                 pcout;
    TimerOutput                        timer;
    parallel::shared::Triangulation<3> triangulation;
    FluidProblem                       fluid;
  };
} // namespace rbc_ifem

#endif

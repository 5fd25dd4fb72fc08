#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/experiments/derived_flow_run.h>
#include <rbc_ifem/ifem/ifem_simulation.h>

#include <deal.II/base/timer.h>

namespace rbc_ifem
{
  void
  run_derived_flow(const RunParameters &run,
                   const FlowDomain    &domain,
                   RunObserver         &observer,
                   const MPI_Comm       communicator,
                   ConditionalOStream  &pcout)
  {
    const Parameters &p = run.model();
    // The run's own sections, on rank 0's clock like the experiment's.
    TimerOutput       timer(MPI_COMM_SELF,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    const std::string text = parameter_text(run.handler());
    IFEMSimulation    simulation(p, text, domain, communicator, timer);
    simulation.add_observer(observer);
    simulation.setup();
    write_parameters(text, p.output_directory, communicator);
    simulation.run();
    write_timing(timer, p.output_directory, communicator);
  }
} // namespace rbc_ifem

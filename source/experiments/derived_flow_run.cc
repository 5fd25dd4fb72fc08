#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/experiments/derived_flow_run.h>
#include <rbc_ifem/ifem/checkpoint.h>
#include <rbc_ifem/ifem/ifem_simulation.h>

#include <deal.II/base/timer.h>

namespace rbc_ifem
{
  std::vector<ParameterChange>
  resumable_run(const Parameters  &study,
                const std::string &directory,
                const unsigned int n_steps)
  {
    const bool resume = study.immersed.resume && Checkpoint(directory).exists();
    const unsigned int interval = study.immersed.checkpoint_interval;
    return {{"Immersed cells", "Resume", resume ? "true" : "false"},
            {"Immersed cells",
             "Checkpoint interval",
             std::to_string(interval > 0 ? interval : n_steps)}};
  }

  void
  run_derived_flow(const RunParameters &run,
                   const FlowDomain    &domain,
                   RunObserver         &observer,
                   const MPI_Comm       communicator,
                   ConditionalOStream  &pcout,
                   const RunOptions    &options)
  {
    const Parameters &p = run.model();
    // The run's own sections, on rank 0's clock like the experiment's.
    TimerOutput       timer(MPI_COMM_SELF,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    const std::string text = parameter_text(run.handler());
    IFEMSimulation    simulation(p, text, domain, communicator, timer, options);
    simulation.add_observer(observer);
    simulation.setup();
    write_together(communicator, [&]() {
      write_parameters(text, p.output_directory, communicator);
    });
    simulation.run();
    write_together(communicator, [&]() {
      write_timing(timer, p.output_directory, communicator);
    });
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/output.h>
#include <rbc_ifem/experiments/experiment.h>

#include <iostream>

namespace rbc_ifem
{
  Experiment::Experiment(const std::string      &name,
                         const Parameters       &parameters,
                         const ParameterHandler &prm,
                         const MPI_Comm          communicator)
    : name(name)
    , parameters(parameters)
    , prm(prm)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
  {}

  void
  Experiment::setup()
  {}

  void
  Experiment::run()
  {
    pcout << "rbc-ifem: experiment '" << name << "' on "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)"
          << std::endl;
    setup();

    const std::string &directory = parameters.output_directory;
    write_parameters(prm, directory, communicator);
    execute();

    write_timing(timer, directory, communicator);
    pcout << "  wrote " << directory << "/: " << written_files(directory)
          << std::endl;
    pcout << "  peak memory: " << peak_memory_mb(communicator)
          << " MB (largest over ranks)" << std::endl;
  }
} // namespace rbc_ifem

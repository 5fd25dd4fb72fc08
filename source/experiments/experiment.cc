#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/base/version.h>
#include <rbc_ifem/experiments/experiment.h>

#include <iostream>

namespace rbc_ifem
{
  Experiment::Experiment(const ExperimentContext &context,
                         const ParametersFile     parameters_file)
    : name(context.name)
    , parameters(context.parameters)
    , communicator(context.communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
    , parameter_file_text(parameter_text(context.prm))
    , parameters_file(parameters_file)
  {}

  void
  Experiment::setup()
  {}

  void
  Experiment::run()
  {
    pcout << "rbc-ifem: experiment '" << name << "' on "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s), "
          << version_line() << std::endl;
    setup();

    const std::string &directory = parameters.output_directory;
    if (parameters_file == ParametersFile::before_work)
      write_parameters(parameter_file_text, directory, communicator);
    execute();
    if (parameters_file == ParametersFile::after_work)
      write_parameters(parameter_file_text, directory, communicator);

    write_timing(timer, directory, communicator);
    pcout << "  wrote " << directory << "/: " << written_files(directory)
          << std::endl;
    pcout << "  peak memory: " << peak_memory_mb(communicator)
          << " MB (largest over ranks)" << std::endl;
  }
} // namespace rbc_ifem

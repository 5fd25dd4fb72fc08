#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/input_files.h>
#include <rbc_ifem/base/interruption.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/base/version.h>
#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/ifem/checkpoint.h>

#include <filesystem>
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
    , parameter_file_text(with_input_copies(parameter_text(context.prm),
                                            context.parameters.input_files()))
    , options(context.options)
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
    check_output_directory();
    setup();

    const std::string &directory             = parameters.output_directory;
    const auto         write_parameters_file = [&]() {
      write_together(communicator, [&]() {
        write_parameters(parameter_file_text, directory, communicator);
        copy_input_files(parameters.input_files(),
                         directory,
                         parameters.immersed.resume,
                         communicator);
      });
    };
    if (parameters_file == ParametersFile::before_work)
      write_parameters_file();
    try
      {
        execute();
      }
    catch (const RunInterrupted &e)
      {
        // The run's parameters.prm holds every value it ran with, --set
        // ones included, so that resuming from it resumes this run.
        throw RunInterrupted(e.signal,
                             std::string(e.what()) +
                               " To go on from there (in this folder): "
                               "rbc-ifem " +
                               directory +
                               "/parameters.prm --set \"Immersed "
                               "cells/Resume=true\"");
      }
    if (parameters_file == ParametersFile::after_work)
      write_parameters_file();

    write_together(communicator,
                   [&]() { write_timing(timer, directory, communicator); });
    pcout << "  wrote " << directory
          << "/: " << written_files(directory, communicator) << std::endl;
    pcout << "  peak memory: " << peak_memory_text(communicator) << std::endl;
  }

  void
  Experiment::check_output_directory() const
  {
    const std::string &directory = parameters.output_directory;
    check_writable(directory, communicator);
    const std::vector<std::string> found = Checkpoint::find_in(directory);
    if (found.empty() || parameters.immersed.resume)
      return;
    if (!options.overwrite)
      throw InputError(
        "Immersed cells/Resume",
        "false",
        "the Output directory " + directory +
          " holds the checkpoints of an earlier run (" + found.front() +
          (found.size() > 1 ?
             " and " + std::to_string(found.size() - 1) + " more" :
             std::string()) +
          "), which this run would replace. To go on from them, set "
          "Immersed cells/Resume = true; to start over, removing them, run "
          "again with --overwrite; or choose another Output directory.");
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      for (const std::string &file : found)
        std::filesystem::remove(file);
    pcout << "  --overwrite: removed the " << found.size()
          << " checkpoint(s) of the earlier run in " << directory << std::endl;
  }
} // namespace rbc_ifem

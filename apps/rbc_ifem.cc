/**
 * rbc-ifem: red blood cells in a pulmonary capillary, simulated with the
 * immersed finite element method, and their carbon monoxide uptake.
 *
 *   rbc-ifem FILE.prm [--set "Subsection/Name=value"]... [--overwrite]
 *            [--force]              run the experiment FILE describes
 *   rbc-ifem --print-parameters     every parameter with its documentation
 *   rbc-ifem --list-experiments     the experiments, one per line
 *   rbc-ifem --version              the version and the git commit
 *   rbc-ifem --help                 usage
 */

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/interruption.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/base/version.h>
#include <rbc_ifem/experiments/registry.h>

#include <deal.II/base/mpi.h>

#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace
{
  using namespace rbc_ifem;

  void
  print_usage(std::ostream &out)
  {
    out
      << "Usage: rbc-ifem FILE.prm            run the experiment in FILE.prm\n"
         "       rbc-ifem FILE.prm --set \"Subsection/Name=value\" ...\n"
         "                                    the same with parameters "
         "changed (several --set\n"
         "                                    allowed, checked like the "
         "file, kept in parameters.prm)\n"
         "       rbc-ifem FILE.prm --overwrite  start over in an Output "
         "directory that holds\n"
         "                                    an earlier run's checkpoints "
         "(removed first)\n"
         "       rbc-ifem FILE.prm --force    run although the size estimate "
         "exceeds the memory\n"
         "       mpirun -np N rbc-ifem FILE.prm  the same on N MPI ranks\n"
         "       rbc-ifem --print-parameters  print every parameter, "
         "documented, with its allowed\n"
         "                                    values, as a valid .prm\n"
         "       rbc-ifem --list-experiments  the names the parameter "
         "Experiment takes, one per line\n"
         "       rbc-ifem --version           the version and the git commit "
         "it was built from\n"
         "       rbc-ifem --help              this text\n"
         "Ready experiments are in prm/; the documentation is in doc/.\n";
  }

  /// The file, the --set changes and the options of a run's command line.
  struct RunArguments
  {
    std::string              filename;
    std::vector<std::string> changes;
    RunOptions               options;
  };

  /**
   * FILE.prm [--set "Subsection/Name=value"]... [--overwrite] [--force], in
   * any order after the file; nothing if not of that form.
   */
  std::optional<RunArguments>
  run_arguments(const std::vector<std::string> &arguments)
  {
    if (arguments.empty() || arguments[0].rfind("-", 0) == 0)
      return {};
    RunArguments run{arguments[0], {}, {}};
    for (std::size_t i = 1; i < arguments.size(); ++i)
      if (arguments[i] == "--overwrite")
        run.options.overwrite = true;
      else if (arguments[i] == "--force")
        run.options.force = true;
      else if (arguments[i] == "--set" && i + 1 < arguments.size())
        run.changes.push_back(arguments[++i]);
      else
        return {};
    return run;
  }

  /**
   * What an option that asks for information prints (--help or -h,
   * --print-parameters, --version, --list-experiments); nothing for any
   * other argument.
   */
  std::function<void(std::ostream &)>
  information(const std::string &option)
  {
    if (option == "--help" || option == "-h")
      return print_usage;
    if (option == "--print-parameters")
      return [](std::ostream &out) { RunParameters().print(out); };
    if (option == "--version")
      return [](std::ostream &out) { out << version_line() << '\n'; };
    if (option == "--list-experiments")
      return [](std::ostream &out) {
        for (const ExperimentType &type : experiment_types())
          out << type.name << '\n';
      };
    return {};
  }

  void
  run(const RunArguments &arguments, const MPI_Comm communicator)
  {
    RunParameters parameters;
    parameters.read(arguments.filename, arguments.changes);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      for (const std::string &warning : parameters.read_warnings())
        std::cerr << "rbc-ifem: warning: " << warning << std::endl;
    parameters.create_experiment(communicator, arguments.options)->run();
  }

  /**
   * Run, and turn what stopped it into a message and the exit code: 1 for
   * an input error, 128 + the signal for an interruption, 2 for a solver
   * that failed or an internal error (which stops every rank), 3 for a file
   * that could not be written (doc/outputs.md lists them).
   */
  int
  run_to_exit_code(const RunArguments &arguments,
                   const MPI_Comm      communicator,
                   const bool          root)
  {
    try
      {
        run(arguments, communicator);
      }
    catch (const InputError &e)
      {
        if (root)
          std::cerr << "rbc-ifem: error: " << e.what() << std::endl;
        return 1;
      }
    catch (const RunInterrupted &e)
      {
        if (root)
          std::cerr << "rbc-ifem: interrupted: " << e.what() << std::endl;
        return 128 + e.signal;
      }
    catch (const SolverFailure &e)
      {
        if (root)
          std::cerr << "rbc-ifem: stopped: " << e.what() << std::endl;
        return 2;
      }
    catch (const OutputError &e)
      {
        const bool alone = Utilities::MPI::n_mpi_processes(communicator) == 1;
        if (!e.known_to_every_rank() || root)
          std::cerr << "rbc-ifem: stopped: " << e.what()
                    << ". The files written before it, and the last "
                       "checkpoint if there is one, are as they were."
                    << std::endl;
        // A failure the other ranks do not know of leaves them waiting in a
        // collective step: only MPI_Abort stops them.
        if (!e.known_to_every_rank() && !alone)
          MPI_Abort(communicator, 3);
        return 3;
      }
    catch (const std::exception &e)
      {
        // It may have happened on this rank alone, with the others waiting
        // for it in a collective step: say where, and stop them all.
        std::cerr << "rbc-ifem: internal error on rank "
                  << Utilities::MPI::this_mpi_process(communicator) << ": "
                  << e.what() << std::endl;
        MPI_Abort(communicator, 2);
        return 2;
      }
    return 0;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  stop_on_interruption();
  const MPI_Comm communicator = MPI_COMM_WORLD;
  const bool     root = Utilities::MPI::this_mpi_process(communicator) == 0;

  const std::vector<std::string> arguments(argv + 1, argv + argc);
  if (arguments.size() == 1)
    if (const auto print = information(arguments[0]))
      {
        if (root)
          print(std::cout);
        return 0;
      }
  const std::optional<RunArguments> run_with = run_arguments(arguments);
  if (!run_with)
    {
      if (root)
        {
          std::cerr << (arguments.empty() ?
                          "rbc-ifem: no parameter file given.\n" :
                          "rbc-ifem: cannot understand the arguments given.\n");
          print_usage(std::cerr);
        }
      return 1;
    }
  return run_to_exit_code(*run_with, communicator, root);
}

/**
 * rbc-ifem: red blood cells in a pulmonary capillary, simulated with the
 * immersed finite element method, and their carbon monoxide uptake.
 *
 *   rbc-ifem FILE.prm               run the experiment FILE describes
 *   rbc-ifem --print-parameters     every parameter with its documentation
 *   rbc-ifem --list-experiments     the experiments, one per line
 *   rbc-ifem --help                 usage
 */

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/experiments/registry.h>

#include <deal.II/base/mpi.h>

#include <iostream>
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
         "       mpirun -np N rbc-ifem FILE.prm  the same on N MPI ranks\n"
         "       rbc-ifem --print-parameters  print every parameter, "
         "documented, as a valid .prm\n"
         "       rbc-ifem --list-experiments  the names the parameter "
         "Experiment takes, one per line\n"
         "       rbc-ifem --help              this text\n"
         "Ready experiments are in prm/; the documentation is in doc/.\n";
  }

  void
  run(const std::string &filename, const MPI_Comm communicator)
  {
    RunParameters parameters;
    parameters.read(filename);
    parameters.create_experiment(communicator)->run();
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   communicator = MPI_COMM_WORLD;
  const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;

  const std::vector<std::string> arguments(argv + 1, argv + argc);
  if (arguments.size() == 1 &&
      (arguments[0] == "--help" || arguments[0] == "-h"))
    {
      if (root)
        print_usage(std::cout);
      return 0;
    }
  if (arguments.size() == 1 && arguments[0] == "--print-parameters")
    {
      if (root)
        RunParameters().print(std::cout);
      return 0;
    }
  if (arguments.size() == 1 && arguments[0] == "--list-experiments")
    {
      if (root)
        for (const ExperimentType &type : experiment_types())
          std::cout << type.name << '\n';
      return 0;
    }
  if (arguments.size() != 1 || arguments[0].rfind("-", 0) == 0)
    {
      if (root)
        {
          if (arguments.empty())
            {
              std::cerr << "rbc-ifem: no parameter file given; these are the "
                           "parameters and their defaults:\n\n";
              RunParameters().print(std::cerr);
              std::cerr << '\n';
            }
          else
            std::cerr << "rbc-ifem: cannot understand the arguments given.\n";
          print_usage(std::cerr);
        }
      return 1;
    }

  try
    {
      run(arguments[0], communicator);
    }
  catch (const InputError &e)
    {
      if (root)
        std::cerr << "rbc-ifem: error: " << e.what() << std::endl;
      return 1;
    }
  catch (const SolverFailure &e)
    {
      if (root)
        std::cerr << "rbc-ifem: stopped: " << e.what() << std::endl;
      return 2;
    }
  catch (const std::exception &e)
    {
      if (root)
        std::cerr << "rbc-ifem: internal error: " << e.what() << std::endl;
      return 2;
    }
  return 0;
}

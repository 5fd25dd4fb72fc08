#include <rbc_ifem/base/output_error.h>

#include <deal.II/base/mpi.templates.h>

namespace rbc_ifem
{
  OutputError::OutputError(const std::string &path, const std::string &cause)
    : std::runtime_error("could not write '" + path + "': " + cause)
  {}

  OutputError::OutputError(const std::string &message)
    : std::runtime_error(message)
    , every_rank(true)
  {}

  bool
  OutputError::known_to_every_rank() const
  {
    return every_rank;
  }

  void
  write_together(const MPI_Comm               communicator,
                 const std::function<void()> &write)
  {
    const unsigned int n_ranks =
      dealii::Utilities::MPI::n_mpi_processes(communicator);
    std::string  message;
    unsigned int failed = n_ranks;
    try
      {
        write();
      }
    catch (const OutputError &e)
      {
        message = e.what();
        failed  = dealii::Utilities::MPI::this_mpi_process(communicator);
      }
    failed = dealii::Utilities::MPI::min(failed, communicator);
    if (failed == n_ranks)
      return;
    message = dealii::Utilities::MPI::broadcast(communicator, message, failed);
    throw OutputError(message);
  }

  void
  write_on_rank_0(const MPI_Comm               communicator,
                  const std::function<void()> &write)
  {
    write_together(communicator, [&]() {
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        write();
    });
  }
} // namespace rbc_ifem

#ifndef rbc_ifem_base_ranks_h
#define rbc_ifem_base_ranks_h

#include <deal.II/base/mpi.h>

namespace rbc_ifem
{
  using namespace dealii;

  /// The number of ranks of @p communicator; 1 in a program that never
  /// started MPI (a serial unit test), where deal.II's would fail.
  inline unsigned int
  n_ranks(const MPI_Comm communicator)
  {
    return Utilities::MPI::job_supports_mpi() ?
             Utilities::MPI::n_mpi_processes(communicator) :
             1;
  }

  /// This process's rank in @p communicator; 0 in a program that never
  /// started MPI.
  inline unsigned int
  this_rank(const MPI_Comm communicator)
  {
    return Utilities::MPI::job_supports_mpi() ?
             Utilities::MPI::this_mpi_process(communicator) :
             0;
  }
} // namespace rbc_ifem

#endif

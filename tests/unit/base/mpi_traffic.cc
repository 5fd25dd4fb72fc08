// mpirun: 2 3

// The counts of MpiTraffic, the program's own wrappers of the MPI
// functions (PMPI), against calls of known size: a sum of 10 doubles is one
// collective call that puts 80 bytes in, a broadcast of 3 ints 12 on every
// rank, an all-gather of 2 ints in place 0 (its send count and type are
// given but not read), and a send of 5 doubles to the next rank one message of
// 40 bytes. The counts are each rank's, so every rank checks its own.

#include <rbc_ifem/base/mpi_traffic.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <array>
#include <string>
#include <vector>

using namespace dealii;
using namespace rbc_ifem;

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   world = MPI_COMM_WORLD;
  const int rank    = Utilities::MPI::this_mpi_process(world);
  const int n_ranks = Utilities::MPI::n_mpi_processes(world);
  if (rank != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports
  Checker check;

  const MpiTraffic       before = MpiTraffic::so_far();
  std::array<double, 10> values{};
  MPI_Allreduce(MPI_IN_PLACE, values.data(), 10, MPI_DOUBLE, MPI_SUM, world);
  std::array<int, 3> broadcast{};
  MPI_Bcast(broadcast.data(), 3, MPI_INT, 0, world);
  std::vector<int> gathered(2 * n_ranks);
  MPI_Allgather(MPI_IN_PLACE, 2, MPI_INT, gathered.data(), 2, MPI_INT, world);
  std::array<double, 5> sent{}, received{};
  MPI_Request           request;
  MPI_Isend(
    sent.data(), 5, MPI_DOUBLE, (rank + 1) % n_ranks, 1, world, &request);
  MPI_Recv(received.data(),
           5,
           MPI_DOUBLE,
           (rank + n_ranks - 1) % n_ranks,
           1,
           world,
           MPI_STATUS_IGNORE);
  MPI_Wait(&request, MPI_STATUS_IGNORE);
  const MpiTraffic during = MpiTraffic::so_far() - before;

  const auto count = [&](const std::string       &what,
                         const unsigned long long counted,
                         const unsigned long long expected) {
    check.holds(what + ": " + std::to_string(counted) + ", expected " +
                  std::to_string(expected),
                counted == expected);
  };
  count("collective calls", during.collectives, 3);
  count("bytes into them", during.collective_bytes, 80 + 12);
  count("messages sent", during.messages, 1);
  count("bytes sent", during.bytes, 40);
  return check.exit_code();
}

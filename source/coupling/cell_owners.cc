#include <rbc_ifem/coupling/cell_owners.h>

namespace rbc_ifem
{
  namespace
  {
    /// The ranks of @p comm; 1 in a program that never started MPI (a
    /// serial test).
    unsigned int
    n_ranks_of(const MPI_Comm comm)
    {
      return Utilities::MPI::job_supports_mpi() ?
               Utilities::MPI::n_mpi_processes(comm) :
               1;
    }
  } // namespace

  CellOwners::CellOwners(const MPI_Comm communicator)
    : communicator(communicator)
    , rank(n_ranks_of(communicator) == 1 ?
             0 :
             Utilities::MPI::this_mpi_process(communicator))
    , n_ranks(n_ranks_of(communicator))
  {}

  unsigned int
  CellOwners::owner(const unsigned int c) const
  {
    return c % n_ranks;
  }

  bool
  CellOwners::owns(const unsigned int c) const
  {
    return owner(c) == rank;
  }

  bool
  CellOwners::shared() const
  {
    return n_ranks > 1;
  }

  void
  CellOwners::add_up(std::vector<Vector<double>> &values,
                     const ArrayView<double>     &scalars) const
  {
    if (!shared())
      return;
    packed.assign(scalars.begin(), scalars.end());
    for (const Vector<double> &cell : values)
      packed.insert(packed.end(), cell.begin(), cell.end());
    Utilities::MPI::sum(packed, communicator, packed);
    auto value = packed.begin();
    for (double &scalar : scalars)
      scalar = *value++;
    for (Vector<double> &cell : values)
      for (double &entry : cell)
        entry = *value++;
  }

  void
  CellOwners::take_smallest(const ArrayView<double> &values) const
  {
    if (shared())
      Utilities::MPI::min(ArrayView<const double>(values.data(), values.size()),
                          communicator,
                          values);
  }
} // namespace rbc_ifem

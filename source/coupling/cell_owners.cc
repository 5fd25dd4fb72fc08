#include <rbc_ifem/base/ranks.h>
#include <rbc_ifem/coupling/cell_owners.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  CellOwners::CellOwners(const MPI_Comm communicator)
    : communicator(communicator)
    , rank(this_rank(communicator))
    , n_ranks(rbc_ifem::n_ranks(communicator))
  {}

  std::vector<unsigned int>
  CellOwners::place(const std::vector<double>       &where,
                    const std::vector<unsigned int> &points)
  {
    AssertDimension(where.size(), points.size());
    if (!shared())
      return {};
    const unsigned int        n_cells = where.size();
    std::vector<unsigned int> order(n_cells);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(),
                     order.end(),
                     [&where](const unsigned int a, const unsigned int b) {
                       return where[a] < where[b];
                     });
    std::vector<unsigned int> placed(n_cells);
    for (unsigned int r = 0; r < n_ranks; ++r)
      for (unsigned int k = r * n_cells / n_ranks;
           k < (r + 1) * n_cells / n_ranks;
           ++k)
        placed[order[k]] = r;

    std::vector<unsigned int> lost;
    for (unsigned int c = 0; c < n_cells && !owner_of.empty(); ++c)
      if (placed[c] != owner_of[c])
        {
          ++handovers;
          if (owner_of[c] == rank)
            lost.push_back(c);
        }
    owner_of = std::move(placed);

    // Every rank placed the cells from its own copy of their positions:
    // if the copies ever differed, a cell could have two owners or none.
    std::vector<unsigned int> owned(2, 0);
    for (unsigned int c = 0; c < n_cells; ++c)
      if (owns(c))
        {
          ++owned[0];
          owned[1] += points[c];
        }
    Utilities::MPI::sum(owned, communicator, owned);
    const unsigned int n_points =
      std::accumulate(points.begin(), points.end(), 0u);
    if (owned[0] != n_cells || owned[1] != n_points)
      throw std::runtime_error(
        "the ranks own " + std::to_string(owned[0]) + " red cells with " +
        std::to_string(owned[1]) + " membrane points, not " +
        std::to_string(n_cells) + " with " + std::to_string(n_points) +
        ": their copies of the cells' positions differ.");
    return lost;
  }

  unsigned int
  CellOwners::n_handovers() const
  {
    return handovers;
  }

  unsigned int
  CellOwners::owner(const unsigned int c) const
  {
    return owner_of.empty() ? c % n_ranks : owner_of[c];
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
  CellOwners::hand_over(const std::vector<unsigned int> &before,
                        std::vector<Vector<double>>     &values) const
  {
    if (!shared())
      return;
    AssertDimension(before.size(), values.size());
    // Both ends list the cells they send to or get from each rank in the
    // cells' order: one message per pair of ranks.
    std::map<unsigned int, std::vector<unsigned int>> sends, receives;
    for (unsigned int c = 0; c < values.size(); ++c)
      if (before[c] == rank && !owns(c))
        sends[owner(c)].push_back(c);
      else if (before[c] != rank && owns(c))
        receives[before[c]].push_back(c);
    constexpr int                    tag = 7003;
    std::vector<MPI_Request>         requests;
    std::vector<std::vector<double>> buffers;
    requests.reserve(sends.size() + receives.size());
    buffers.reserve(sends.size() + receives.size());
    for (const auto &[other, cells] : receives)
      {
        std::size_t size = 0;
        for (const unsigned int c : cells)
          size += values[c].size();
        buffers.emplace_back(size);
        requests.emplace_back();
        AssertThrowMPI(MPI_Irecv(buffers.back().data(),
                                 size,
                                 MPI_DOUBLE,
                                 other,
                                 tag,
                                 communicator,
                                 &requests.back()));
      }
    for (const auto &[other, cells] : sends)
      {
        buffers.emplace_back();
        for (const unsigned int c : cells)
          buffers.back().insert(buffers.back().end(),
                                values[c].begin(),
                                values[c].end());
        requests.emplace_back();
        AssertThrowMPI(MPI_Isend(buffers.back().data(),
                                 buffers.back().size(),
                                 MPI_DOUBLE,
                                 other,
                                 tag,
                                 communicator,
                                 &requests.back()));
      }
    AssertThrowMPI(
      MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE));
    auto buffer = buffers.begin();
    for (const auto &[other, cells] : receives)
      {
        auto value = buffer->begin();
        for (const unsigned int c : cells)
          for (double &entry : values[c])
            entry = *value++;
        ++buffer;
      }
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

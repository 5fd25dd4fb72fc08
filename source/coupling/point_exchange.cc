#include <rbc_ifem/base/ranks.h>
#include <rbc_ifem/coupling/point_exchange.h>

#include <boost/serialization/vector.hpp>

#include <map>

namespace rbc_ifem
{
  namespace
  {
    /// Tags of the two directions, above those deal.II uses.
    constexpr int to_readers_tag     = 7001;
    constexpr int to_fluid_ranks_tag = 7002;
  } // namespace

  std::vector<PointExchange::Route>
  PointExchange::to_routes(const RouteMap &map)
  {
    std::vector<Route> routes;
    for (const auto &[other, points] : map)
      routes.push_back({other, points});
    return routes;
  }

  PointExchange::PointExchange(const MPI_Comm                   communicator,
                               const std::vector<unsigned int> &fluid_ranks,
                               const std::vector<unsigned int> &owners,
                               const std::vector<unsigned int> &read)
    : PointExchange(communicator, fluid_ranks, owners)
  {
    // What a rank reads it asks of the points' fluid ranks, which learn
    // from the asking whom to send what.
    const unsigned int rank = this_rank(communicator);
    RouteMap           asked;
    for (const unsigned int i : read)
      if (fluid_ranks[i] != rank)
        asked[fluid_ranks[i]].push_back(i);
    reader_receives = to_routes(asked);
    reader_sends = to_routes(Utilities::MPI::some_to_some(communicator, asked));
  }

  PointExchange::PointExchange(const MPI_Comm                   communicator,
                               const std::vector<unsigned int> &fluid_ranks,
                               const std::vector<unsigned int> &owners)
    : communicator(communicator)
  {
    AssertDimension(fluid_ranks.size(), owners.size());
    // Back to the fluid ranks: both ends know the owners and the fluid
    // ranks of every point, so no one needs to ask.
    const unsigned int rank = this_rank(communicator);
    RouteMap           sends, receives;
    for (unsigned int i = 0; i < fluid_ranks.size(); ++i)
      if (owners[i] == rank && fluid_ranks[i] != rank)
        sends[fluid_ranks[i]].push_back(i);
      else if (fluid_ranks[i] == rank && owners[i] != rank)
        receives[owners[i]].push_back(i);
    fluid_sends    = to_routes(sends);
    fluid_receives = to_routes(receives);
  }

  void
  PointExchange::to_readers(std::vector<Tensor<1, 3>> &values) const
  {
    exchange(reader_sends, reader_receives, to_readers_tag, values);
  }

  void
  PointExchange::to_fluid_ranks(std::vector<Tensor<1, 3>> &values) const
  {
    exchange(fluid_sends, fluid_receives, to_fluid_ranks_tag, values);
  }

  unsigned int
  PointExchange::n_points_travelling() const
  {
    unsigned int n = 0;
    for (const auto *routes :
         {&reader_sends, &reader_receives, &fluid_sends, &fluid_receives})
      for (const Route &route : *routes)
        n += route.points.size();
    return n;
  }

  void
  PointExchange::exchange(const std::vector<Route>  &sends,
                          const std::vector<Route>  &receives,
                          const int                  tag,
                          std::vector<Tensor<1, 3>> &values) const
  {
    std::vector<MPI_Request> requests(sends.size() + receives.size());
    receive_buffers.resize(receives.size());
    send_buffers.resize(sends.size());
    for (unsigned int k = 0; k < receives.size(); ++k)
      {
        receive_buffers[k].resize(3 * receives[k].points.size());
        const int error = MPI_Irecv(receive_buffers[k].data(),
                                    receive_buffers[k].size(),
                                    MPI_DOUBLE,
                                    receives[k].rank,
                                    tag,
                                    communicator,
                                    &requests[k]);
        AssertThrowMPI(error);
      }
    for (unsigned int k = 0; k < sends.size(); ++k)
      {
        std::vector<double> &buffer = send_buffers[k];
        buffer.clear();
        for (const unsigned int i : sends[k].points)
          for (unsigned int d = 0; d < 3; ++d)
            buffer.push_back(values[i][d]);
        const int error = MPI_Isend(buffer.data(),
                                    buffer.size(),
                                    MPI_DOUBLE,
                                    sends[k].rank,
                                    tag,
                                    communicator,
                                    &requests[receives.size() + k]);
        AssertThrowMPI(error);
      }
    const int error =
      MPI_Waitall(requests.size(), requests.data(), MPI_STATUSES_IGNORE);
    AssertThrowMPI(error);
    for (unsigned int k = 0; k < receives.size(); ++k)
      {
        auto value = receive_buffers[k].begin();
        for (const unsigned int i : receives[k].points)
          for (unsigned int d = 0; d < 3; ++d)
            values[i][d] = *value++;
      }
  }
} // namespace rbc_ifem

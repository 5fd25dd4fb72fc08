#ifndef rbc_ifem_coupling_point_exchange_h
#define rbc_ifem_coupling_point_exchange_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <map>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Point-to-point traffic of values at membrane points between the two
   * ranks each point has (doc/design.md, Section 9): its fluid rank, whose
   * fluid cell holds it (ImmersedCoupling::point_ranks()), where velocities
   * are interpolated and forces spread; and its owner, whose rows of the
   * tangent stiffness K hold it (CellPopulation::point_owners()). With the
   * cells owned by where they are and the fluid mesh in slabs along the
   * same axis (MeshZone), the two are the same rank for most points: only
   * the points of cells that straddle a slab boundary, and the contact
   * partners a rank's stiffness reads across one, travel. Nothing is
   * summed over all ranks.
   *
   * Values come one Tensor<1, 3> per point, in the order of
   * CellPopulation::points(); a rank uses the entries of its points only.
   */
  class PointExchange
  {
  public:
    /**
     * Set up the traffic: @p fluid_ranks and @p owners, per point, the
     * same on every rank; @p read the points whose values this rank needs
     * (sorted: its rows of K and what they read). Collective: each rank
     * asks the fluid ranks of its @p read points for them, once.
     */
    PointExchange(const MPI_Comm                   communicator,
                  const std::vector<unsigned int> &fluid_ranks,
                  const std::vector<unsigned int> &owners,
                  const std::vector<unsigned int> &read);

    /**
     * Set up the traffic to the fluid ranks only (to_fluid_ranks()), for
     * values that the owners alone have, such as the membrane forces
     * (CellPopulation::compute_owned_forces()). Both ends know every
     * point's two ranks, so this is not collective.
     */
    PointExchange(const MPI_Comm                   communicator,
                  const std::vector<unsigned int> &fluid_ranks,
                  const std::vector<unsigned int> &owners);

    /**
     * @p values holds this rank's fluid points' values on entry (as
     * ImmersedCoupling::evaluate() leaves them); on exit also those of
     * every point it reads, from their fluid ranks.
     */
    void
    to_readers(std::vector<Tensor<1, 3>> &values) const;

    /**
     * @p values holds the values of the points this rank owns on entry
     * (as the rows of K); on exit also those of this rank's fluid points,
     * from their owners, for spreading.
     */
    void
    to_fluid_ranks(std::vector<Tensor<1, 3>> &values) const;

    /// The points this rank sends and receives per exchange in both
    /// directions, for the load-balance counters.
    unsigned int
    n_points_travelling() const;

  private:
    /// The points that go to or come from one other rank, ascending.
    struct Route
    {
      unsigned int              rank;
      std::vector<unsigned int> points;
    };

    /// The points of each other rank, by rank.
    using RouteMap = std::map<unsigned int, std::vector<unsigned int>>;

    /// The routes of @p map, by ascending rank.
    static std::vector<Route>
    to_routes(const RouteMap &map);

    /// Send the @p sends' values, receive the @p receives' into @p values.
    void
    exchange(const std::vector<Route>  &sends,
             const std::vector<Route>  &receives,
             int                        tag,
             std::vector<Tensor<1, 3>> &values) const;

    const MPI_Comm     communicator;
    std::vector<Route> reader_sends, reader_receives;
    std::vector<Route> fluid_sends, fluid_receives;
    /// One buffer per route, kept so that an exchange inside every linear
    /// iteration allocates nothing after the first.
    mutable std::vector<std::vector<double>> send_buffers, receive_buffers;
  };
} // namespace rbc_ifem

#endif

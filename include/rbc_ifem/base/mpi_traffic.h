#ifndef rbc_ifem_base_mpi_traffic_h
#define rbc_ifem_base_mpi_traffic_h

namespace rbc_ifem
{
  /**
   * What this rank has asked of MPI since it started, counted by wrappers
   * of the MPI functions through MPI's profiling interface (PMPI): the
   * program defines MPI_Allreduce, MPI_Isend and the others, counts the
   * call and hands it on to PMPI_Allreduce, PMPI_Isend, unchanged. Every
   * library the program loads (deal.II, Trilinos, PETSc) calls them too, so
   * the counts are the whole program's. The difference of two counts is
   * what happened between them (a run's steps: RunReport::communication()).
   */
  struct MpiTraffic
  {
    /// Collective calls: reductions, broadcasts, gathers, scatters,
    /// all-to-alls, scans, barriers and communicator duplicates and splits.
    unsigned long long collectives = 0;
    /// Point-to-point sends (blocking or not).
    unsigned long long messages = 0;
    /// The bytes those sends carried.
    unsigned long long bytes = 0;
    /// The bytes this rank put into the collective calls: its send buffer
    /// (what it receives, for a scatter), so that a sum over all membrane
    /// points shows as their number of values, whatever the ranks.
    unsigned long long collective_bytes = 0;

    /// The counts of this rank so far.
    static MpiTraffic
    so_far();

    /// The counts between @p earlier and these.
    MpiTraffic
    operator-(const MpiTraffic &earlier) const;
  };
} // namespace rbc_ifem

#endif

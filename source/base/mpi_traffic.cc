#include <rbc_ifem/base/mpi_traffic.h>

#include <mpi.h>

#include <atomic>

// The wrappers of MpiTraffic. Defined in the program, they take the place
// of the MPI library's functions for every caller (the dynamic linker finds
// the program's first); each counts and calls the PMPI_ function, which
// does what the MPI_ function would have.

namespace
{
  std::atomic<unsigned long long> n_collectives{0};
  std::atomic<unsigned long long> n_messages{0};
  std::atomic<unsigned long long> n_bytes{0};
  std::atomic<unsigned long long> n_collective_bytes{0};

  /// The bytes of @p count entries of @p type.
  unsigned long long
  bytes_of(const long long count, MPI_Datatype type)
  {
    if (type == MPI_DATATYPE_NULL || count <= 0)
      return 0;
    // The _x variant: deal.II's types for large messages are larger than
    // an int can count.
    MPI_Count size = 0;
    PMPI_Type_size_x(type, &size);
    return size > 0 ? static_cast<unsigned long long>(count) * size : 0;
  }

  /// The number of ranks of @p c.
  long long
  ranks_in(MPI_Comm c)
  {
    int n_ranks = 0;
    PMPI_Comm_size(c, &n_ranks);
    return n_ranks;
  }

  /// The bytes of the counts @p counts, one per rank of @p c, of @p type.
  unsigned long long
  bytes_of(const int *counts, MPI_Datatype type, MPI_Comm c)
  {
    const long long n_ranks = ranks_in(c);
    long long       count   = 0;
    for (long long r = 0; r < n_ranks; ++r)
      count += counts[r];
    return bytes_of(count, type);
  }

  void
  count_message(const int count, MPI_Datatype type)
  {
    ++n_messages;
    n_bytes += bytes_of(count, type);
  }
} // namespace

/// One wrapper per collective: count the call and the @p bytes this rank
/// puts in (its send buffer; what it receives for a scatter), then make it.
#define COLLECTIVE(name, parameters, arguments, bytes) \
  extern "C" int name parameters                       \
  {                                                    \
    ++n_collectives;                                   \
    n_collective_bytes += bytes;                       \
    return P##name arguments;                          \
  }

COLLECTIVE(MPI_Barrier, (MPI_Comm c), (c), 0)
COLLECTIVE(MPI_Ibarrier, (MPI_Comm c, MPI_Request *r), (c, r), 0)
COLLECTIVE(MPI_Bcast,
           (void *b, int n, MPI_Datatype t, int root, MPI_Comm c),
           (b, n, t, root, c),
           bytes_of(n, t))
COLLECTIVE(
  MPI_Allreduce,
  (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, MPI_Comm c),
  (s, r, n, t, o, c),
  bytes_of(n, t))
COLLECTIVE(MPI_Iallreduce,
           (const void  *s,
            void        *r,
            int          n,
            MPI_Datatype t,
            MPI_Op       o,
            MPI_Comm     c,
            MPI_Request *q),
           (s, r, n, t, o, c, q),
           bytes_of(n, t))
COLLECTIVE(MPI_Reduce,
           (const void  *s,
            void        *r,
            int          n,
            MPI_Datatype t,
            MPI_Op       o,
            int          root,
            MPI_Comm     c),
           (s, r, n, t, o, root, c),
           bytes_of(n, t))
COLLECTIVE(
  MPI_Scan,
  (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, MPI_Comm c),
  (s, r, n, t, o, c),
  bytes_of(n, t))
COLLECTIVE(
  MPI_Exscan,
  (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, MPI_Comm c),
  (s, r, n, t, o, c),
  bytes_of(n, t))
COLLECTIVE(MPI_Allgather,
           (const void  *s,
            int          ns,
            MPI_Datatype ts,
            void        *r,
            int          nr,
            MPI_Datatype tr,
            MPI_Comm     c),
           (s, ns, ts, r, nr, tr, c),
           s == MPI_IN_PLACE ? 0 : bytes_of(ns, ts))
COLLECTIVE(MPI_Allgatherv,
           (const void  *s,
            int          ns,
            MPI_Datatype ts,
            void        *r,
            const int   *nr,
            const int   *d,
            MPI_Datatype tr,
            MPI_Comm     c),
           (s, ns, ts, r, nr, d, tr, c),
           s == MPI_IN_PLACE ? 0 : bytes_of(ns, ts))
COLLECTIVE(MPI_Gather,
           (const void  *s,
            int          ns,
            MPI_Datatype ts,
            void        *r,
            int          nr,
            MPI_Datatype tr,
            int          root,
            MPI_Comm     c),
           (s, ns, ts, r, nr, tr, root, c),
           s == MPI_IN_PLACE ? 0 : bytes_of(ns, ts))
COLLECTIVE(MPI_Gatherv,
           (const void  *s,
            int          ns,
            MPI_Datatype ts,
            void        *r,
            const int   *nr,
            const int   *d,
            MPI_Datatype tr,
            int          root,
            MPI_Comm     c),
           (s, ns, ts, r, nr, d, tr, root, c),
           s == MPI_IN_PLACE ? 0 : bytes_of(ns, ts))
COLLECTIVE(MPI_Scatter,
           (const void  *s,
            int          ns,
            MPI_Datatype ts,
            void        *r,
            int          nr,
            MPI_Datatype tr,
            int          root,
            MPI_Comm     c),
           (s, ns, ts, r, nr, tr, root, c),
           r == MPI_IN_PLACE ? 0 : bytes_of(nr, tr))
COLLECTIVE(MPI_Scatterv,
           (const void  *s,
            const int   *ns,
            const int   *d,
            MPI_Datatype ts,
            void        *r,
            int          nr,
            MPI_Datatype tr,
            int          root,
            MPI_Comm     c),
           (s, ns, d, ts, r, nr, tr, root, c),
           r == MPI_IN_PLACE ? 0 : bytes_of(nr, tr))
COLLECTIVE(MPI_Alltoall,
           (const void  *s,
            int          ns,
            MPI_Datatype ts,
            void        *r,
            int          nr,
            MPI_Datatype tr,
            MPI_Comm     c),
           (s, ns, ts, r, nr, tr, c),
           s == MPI_IN_PLACE ? 0 : bytes_of(ns, ts) * ranks_in(c))
COLLECTIVE(MPI_Alltoallv,
           (const void  *s,
            const int   *ns,
            const int   *ds,
            MPI_Datatype ts,
            void        *r,
            const int   *nr,
            const int   *dr,
            MPI_Datatype tr,
            MPI_Comm     c),
           (s, ns, ds, ts, r, nr, dr, tr, c),
           s == MPI_IN_PLACE ? 0 : bytes_of(ns, ts, c))
COLLECTIVE(
  MPI_Reduce_scatter,
  (const void *s, void *r, const int *n, MPI_Datatype t, MPI_Op o, MPI_Comm c),
  (s, r, n, t, o, c),
  bytes_of(n, t, c))
COLLECTIVE(MPI_Comm_dup, (MPI_Comm c, MPI_Comm *d), (c, d), 0)
COLLECTIVE(MPI_Comm_split,
           (MPI_Comm c, int k, int r, MPI_Comm *d),
           (c, k, r, d),
           0)

/// One wrapper per way to send: count the message and its bytes.
#define SEND(name, parameters, arguments) \
  extern "C" int name parameters          \
  {                                       \
    count_message(n, t);                  \
    return P##name arguments;             \
  }

SEND(MPI_Send,
     (const void *b, int n, MPI_Datatype t, int to, int tag, MPI_Comm c),
     (b, n, t, to, tag, c))
SEND(MPI_Ssend,
     (const void *b, int n, MPI_Datatype t, int to, int tag, MPI_Comm c),
     (b, n, t, to, tag, c))
SEND(MPI_Isend,
     (const void  *b,
      int          n,
      MPI_Datatype t,
      int          to,
      int          tag,
      MPI_Comm     c,
      MPI_Request *q),
     (b, n, t, to, tag, c, q))
SEND(MPI_Issend,
     (const void  *b,
      int          n,
      MPI_Datatype t,
      int          to,
      int          tag,
      MPI_Comm     c,
      MPI_Request *q),
     (b, n, t, to, tag, c, q))

namespace rbc_ifem
{
  MpiTraffic
  MpiTraffic::so_far()
  {
    return {n_collectives.load(),
            n_messages.load(),
            n_bytes.load(),
            n_collective_bytes.load()};
  }

  MpiTraffic
  MpiTraffic::operator-(const MpiTraffic &earlier) const
  {
    return {collectives - earlier.collectives,
            messages - earlier.messages,
            bytes - earlier.bytes,
            collective_bytes - earlier.collective_bytes};
  }
} // namespace rbc_ifem

/*
 * Counts what a run asks of MPI, per rank: the collective calls and the
 * point-to-point messages and bytes it sends. Built as a shared library and
 * preloaded (benchmarks/scaling.sh does both), it wraps the MPI functions
 * through the profiling interface (PMPI) and changes nothing they do.
 *
 * At MPI_Finalize each rank writes one line to $RBC_MPI_COUNTS.RANK:
 *
 *   rank collectives messages bytes
 *
 * A run of k steps and one of 2k steps of the same case differ by k steps'
 * worth: that difference over k is what one step costs.
 */
#include <mpi.h>

#include <stdio.h>
#include <stdlib.h>

static long long collectives = 0;
static long long messages    = 0;
static long long bytes       = 0;

static void
count_message(const int count, MPI_Datatype type)
{
  int size = 0;
  PMPI_Type_size(type, &size);
  ++messages;
  bytes += (long long)count * size;
}

/* One wrapper per collective: count the call, then make it. */
#define COLLECTIVE(name, parameters, arguments) \
  int name parameters                          \
  {                                            \
    ++collectives;                             \
    return P##name arguments;                  \
  }

COLLECTIVE(MPI_Barrier, (MPI_Comm c), (c))
COLLECTIVE(MPI_Ibarrier, (MPI_Comm c, MPI_Request *r), (c, r))
COLLECTIVE(MPI_Bcast,
           (void *b, int n, MPI_Datatype t, int root, MPI_Comm c),
           (b, n, t, root, c))
COLLECTIVE(MPI_Allreduce,
           (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o,
            MPI_Comm c),
           (s, r, n, t, o, c))
COLLECTIVE(MPI_Iallreduce,
           (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o,
            MPI_Comm c, MPI_Request *q),
           (s, r, n, t, o, c, q))
COLLECTIVE(MPI_Reduce,
           (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o, int root,
            MPI_Comm c),
           (s, r, n, t, o, root, c))
COLLECTIVE(MPI_Scan,
           (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o,
            MPI_Comm c),
           (s, r, n, t, o, c))
COLLECTIVE(MPI_Exscan,
           (const void *s, void *r, int n, MPI_Datatype t, MPI_Op o,
            MPI_Comm c),
           (s, r, n, t, o, c))
COLLECTIVE(MPI_Allgather,
           (const void *s, int ns, MPI_Datatype ts, void *r, int nr,
            MPI_Datatype tr, MPI_Comm c),
           (s, ns, ts, r, nr, tr, c))
COLLECTIVE(MPI_Allgatherv,
           (const void *s, int ns, MPI_Datatype ts, void *r, const int *nr,
            const int *d, MPI_Datatype tr, MPI_Comm c),
           (s, ns, ts, r, nr, d, tr, c))
COLLECTIVE(MPI_Gather,
           (const void *s, int ns, MPI_Datatype ts, void *r, int nr,
            MPI_Datatype tr, int root, MPI_Comm c),
           (s, ns, ts, r, nr, tr, root, c))
COLLECTIVE(MPI_Gatherv,
           (const void *s, int ns, MPI_Datatype ts, void *r, const int *nr,
            const int *d, MPI_Datatype tr, int root, MPI_Comm c),
           (s, ns, ts, r, nr, d, tr, root, c))
COLLECTIVE(MPI_Scatter,
           (const void *s, int ns, MPI_Datatype ts, void *r, int nr,
            MPI_Datatype tr, int root, MPI_Comm c),
           (s, ns, ts, r, nr, tr, root, c))
COLLECTIVE(MPI_Scatterv,
           (const void *s, const int *ns, const int *d, MPI_Datatype ts,
            void *r, int nr, MPI_Datatype tr, int root, MPI_Comm c),
           (s, ns, d, ts, r, nr, tr, root, c))
COLLECTIVE(MPI_Alltoall,
           (const void *s, int ns, MPI_Datatype ts, void *r, int nr,
            MPI_Datatype tr, MPI_Comm c),
           (s, ns, ts, r, nr, tr, c))
COLLECTIVE(MPI_Alltoallv,
           (const void *s, const int *ns, const int *ds, MPI_Datatype ts,
            void *r, const int *nr, const int *dr, MPI_Datatype tr,
            MPI_Comm c),
           (s, ns, ds, ts, r, nr, dr, tr, c))
COLLECTIVE(MPI_Reduce_scatter,
           (const void *s, void *r, const int *n, MPI_Datatype t, MPI_Op o,
            MPI_Comm c),
           (s, r, n, t, o, c))
COLLECTIVE(MPI_Comm_dup, (MPI_Comm c, MPI_Comm *d), (c, d))
COLLECTIVE(MPI_Comm_split, (MPI_Comm c, int k, int r, MPI_Comm *d),
           (c, k, r, d))

/* One wrapper per way to send: count the message and its bytes. */
#define SEND(name, parameters, arguments)       \
  int name parameters                           \
  {                                             \
    count_message(n, t);                        \
    return P##name arguments;                   \
  }

SEND(MPI_Send,
     (const void *b, int n, MPI_Datatype t, int to, int tag, MPI_Comm c),
     (b, n, t, to, tag, c))
SEND(MPI_Ssend,
     (const void *b, int n, MPI_Datatype t, int to, int tag, MPI_Comm c),
     (b, n, t, to, tag, c))
SEND(MPI_Isend,
     (const void *b, int n, MPI_Datatype t, int to, int tag, MPI_Comm c,
      MPI_Request *q),
     (b, n, t, to, tag, c, q))
SEND(MPI_Issend,
     (const void *b, int n, MPI_Datatype t, int to, int tag, MPI_Comm c,
      MPI_Request *q),
     (b, n, t, to, tag, c, q))

int
MPI_Finalize(void)
{
  const char *prefix = getenv("RBC_MPI_COUNTS");
  if (prefix != NULL)
    {
      int rank = 0;
      PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
      char path[4096];
      snprintf(path, sizeof(path), "%s.%d", prefix, rank);
      FILE *file = fopen(path, "w");
      if (file != NULL)
        {
          fprintf(file, "%d %lld %lld %lld\n", rank, collectives, messages,
                  bytes);
          fclose(file);
        }
    }
  return PMPI_Finalize();
}

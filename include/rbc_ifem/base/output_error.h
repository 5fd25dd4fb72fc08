#ifndef rbc_ifem_base_output_error_h
#define rbc_ifem_base_output_error_h

#include <deal.II/base/mpi.h>

#include <functional>
#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  /**
   * A file that could not be written, with the cause the system gave (its
   * strerror, such as "No space left on device"). The run stops with this
   * message and main() exits with status 3; the file's temporary `.part` is
   * removed, and what was written before it (the last checkpoint, the files
   * of earlier outputs) stays as it was.
   */
  class OutputError : public std::runtime_error
  {
  public:
    /// @p path could not be written because of @p cause.
    OutputError(const std::string &path, const std::string &cause);

    /**
     * Whether every rank has thrown it (write_together()), so that the ranks
     * can stop together without MPI_Abort; else only the rank that failed
     * knows.
     */
    bool
    known_to_every_rank() const;

  private:
    /// The failure @p message, known to every rank.
    explicit OutputError(const std::string &message);

    bool every_rank = false;

    friend void
    write_together(const MPI_Comm, const std::function<void()> &);
  };

  /**
   * Call @p write on every rank of @p communicator (it may write on some
   * ranks only); if it throws OutputError on any rank, throw the first
   * failing rank's OutputError on all of them, so that a
   * file one rank could not write stops the run on every rank at the same
   * point instead of leaving the others waiting in a collective step.
   */
  void
  write_together(const MPI_Comm               communicator,
                 const std::function<void()> &write);

  /// write_together() of @p write, called on rank 0 of @p communicator
  /// alone: the tables that rank 0 writes for all.
  void
  write_on_rank_0(const MPI_Comm               communicator,
                  const std::function<void()> &write);
} // namespace rbc_ifem

#endif

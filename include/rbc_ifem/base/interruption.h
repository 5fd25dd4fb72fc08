#ifndef rbc_ifem_base_interruption_h
#define rbc_ifem_base_interruption_h

#include <deal.II/base/mpi.h>

#include <csignal>
#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  /**
   * From now on, SIGINT and SIGTERM outside an InterruptionGuard stop the
   * process at once with a message on standard error and the status 128 +
   * the signal: while a run sets up (meshes, the first DM solve) there is
   * nothing to save, and the files it writes appear whole or not at all.
   * main() calls it first.
   */
  void
  stop_on_interruption();

  /**
   * SIGINT (Ctrl-C) and SIGTERM (what batch systems send before they kill a
   * job) caught while this object lives: a signal no longer ends the
   * process but sets a flag that a time loop reads between two steps
   * (received()), so that the run can write a checkpoint and stop cleanly.
   * The handlers that were there before come back when it is destroyed.
   */
  class InterruptionGuard
  {
  public:
    InterruptionGuard();
    ~InterruptionGuard();
    InterruptionGuard(const InterruptionGuard &) = delete;
    InterruptionGuard &
    operator=(const InterruptionGuard &) = delete;

    /// The signal any rank of @p communicator has received (0: none).
    /// Collective: every rank must call it at the same point.
    int
    received(const MPI_Comm communicator) const;

  private:
    using Handler = void (*)(int);
    Handler previous_interrupt, previous_terminate;
  };

  /**
   * A run that stopped on a signal after it had saved what a resume needs.
   * main() prints the message and exits with status 128 + the signal (130
   * for SIGINT, 143 for SIGTERM), as a shell reports a signal.
   */
  class RunInterrupted : public std::runtime_error
  {
  public:
    RunInterrupted(const int signal, const std::string &message)
      : std::runtime_error(message)
      , signal(signal)
    {}

    const int signal;
  };

  /// "SIGINT", "SIGTERM" or "signal N".
  std::string
  signal_name(const int signal);
} // namespace rbc_ifem

#endif

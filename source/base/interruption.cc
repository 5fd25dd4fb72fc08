#include <rbc_ifem/base/interruption.h>

#include <unistd.h>

namespace rbc_ifem
{
  namespace
  {
    /// The last signal caught, 0 for none: all a handler may safely do.
    volatile std::sig_atomic_t caught_signal = 0;

    extern "C" void
    note_signal(const int signal)
    {
      caught_signal = signal;
    }

    /// Say why, and end the process as the signal would have (write() and
    /// _exit() are what a handler may call).
    extern "C" void
    stop_at_once(const int signal)
    {
      const char message[] =
        "rbc-ifem: interrupted outside a time loop (while setting up or "
        "writing its last files): the files it wrote are complete; a "
        "flowing run resumes from its last checkpoint, if it wrote one.\n";
      [[maybe_unused]] const auto written =
        ::write(STDERR_FILENO, message, sizeof(message) - 1);
      ::_exit(128 + signal);
    }
  } // namespace

  void
  stop_on_interruption()
  {
    std::signal(SIGINT, stop_at_once);
    std::signal(SIGTERM, stop_at_once);
  }

  InterruptionGuard::InterruptionGuard()
  {
    caught_signal      = 0;
    previous_interrupt = std::signal(SIGINT, note_signal);
    previous_terminate = std::signal(SIGTERM, note_signal);
  }

  InterruptionGuard::~InterruptionGuard()
  {
    std::signal(SIGINT, previous_interrupt);
    std::signal(SIGTERM, previous_terminate);
  }

  int
  InterruptionGuard::received(const MPI_Comm communicator) const
  {
    return dealii::Utilities::MPI::max(static_cast<int>(caught_signal),
                                       communicator);
  }

  std::string
  signal_name(const int signal)
  {
    if (signal == SIGINT)
      return "SIGINT";
    if (signal == SIGTERM)
      return "SIGTERM";
    return "signal " + std::to_string(signal);
  }
} // namespace rbc_ifem

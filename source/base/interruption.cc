#include <rbc_ifem/base/interruption.h>

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
  } // namespace

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

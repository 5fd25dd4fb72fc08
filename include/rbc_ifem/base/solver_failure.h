#ifndef rbc_ifem_base_solver_failure_h
#define rbc_ifem_base_solver_failure_h

#include <stdexcept>
#include <string>

namespace rbc_ifem
{
  /**
   * A solver that did not converge, or produced a non-finite field. The run
   * stops with this message (main() exits with status 2) instead of carrying
   * on with a wrong or NaN solution, unless the caller can try again
   * otherwise (the O2 transit's steps to a tolerance try a failed step
   * again shorter).
   */
  class SolverFailure : public std::runtime_error
  {
  public:
    explicit SolverFailure(const std::string &message)
      : std::runtime_error(message)
    {}
  };
} // namespace rbc_ifem

#endif

#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/step_control.h>

#include <algorithm>
#include <cmath>

namespace rbc_ifem
{
  StepControl::StepControl(const double first_step,
                           const double tolerance,
                           const double largest_step)
    : tolerance(tolerance)
    , largest_step(largest_step)
    , step(std::min(first_step, largest_step))
  {}

  double
  StepControl::next(const double time, const double stop) const
  {
    // Land on the stop without a sliver of a step before it, and without
    // a step after it more than twice as long (BDF2's ω stays below 2):
    // from two steps before the stop, go there in two halves.
    const double remaining = stop - time;
    cut                    = remaining <= 1.1 * step;
    if (std::abs(remaining - step) <= 1e-9 * step)
      last_tried = step; // fixed steps that divide the way to the stop
    else if (cut)
      last_tried = remaining;
    else
      last_tried = remaining < 2. * step ? remaining / 2. : step;
    return last_tried;
  }

  bool
  StepControl::judge(const double error)
  {
    // Fixed steps; or the first two, which have no estimate.
    if (tolerance == 0. || error == 0.)
      return true;
    const double ratio = error / tolerance;
    const double factor =
      std::clamp(0.9 * std::cbrt(1. / std::max(ratio, 1e-30)), 0.2, 2.);
    if (ratio <= 1.)
      {
        // A step shortened to reach the stop says little of the next.
        if (!cut && last_tried == step)
          step = std::min(largest_step, step * factor);
        return true;
      }
    step = last_tried * factor;
    ++rejected;
    if (step < 1e-12)
      throw SolverFailure("O2 transport: the step fell below 1e-12 s to "
                          "meet Transit/Time step tolerance.");
    return false;
  }

  unsigned int
  StepControl::n_rejected() const
  {
    return rejected;
  }

  std::vector<double>
  output_times(const double duration, const double period)
  {
    std::vector<double> times;
    for (unsigned int k = 1; k * period < duration - 1e-9 * period; ++k)
      times.push_back(k * period);
    times.push_back(duration);
    return times;
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/ifem/volume_watch.h>

#include <cmath>
#include <limits>

namespace rbc_ifem
{
  VolumeWatch::VolumeWatch(const unsigned int n_cells, const double bound)
    : bound(bound)
    , last_change(n_cells, std::numeric_limits<double>::quiet_NaN())
    , last_increment(n_cells, 0.)
    , growing(n_cells, 0)
  {}

  std::string
  VolumeWatch::add(const std::vector<double> &volume_changes)
  {
    for (unsigned int c = 0; c < volume_changes.size(); ++c)
      {
        const double change = volume_changes[c];
        if (!(std::abs(change) <= bound))
          return "the volume of cell " + std::to_string(c) + " changed by " +
                 to_text(100. * change) +
                 "%, more than Immersed cells/Maximum volume change = " +
                 to_text(100. * bound) +
                 "%: the coupling is unstable or the step too long; reduce "
                 "Time/Time step";
        const double increment = change - last_change[c];
        const bool   alternating_and_growing =
          std::abs(increment) > smallest_increment &&
          increment * last_increment[c] < 0. &&
          std::abs(increment) > std::abs(last_increment[c]);
        growing[c]        = alternating_and_growing ? growing[c] + 1 : 0;
        last_change[c]    = change;
        last_increment[c] = std::isfinite(increment) ? increment : 0.;
        if (growing[c] >= oscillating_steps)
          return "the volume of cell " + std::to_string(c) +
                 " oscillates from step to step with a growing amplitude "
                 "(now " +
                 to_text(100. * std::abs(increment)) + "% a step, " +
                 std::to_string(oscillating_steps) +
                 " steps in a row): the coupling is unstable; reduce "
                 "Time/Time step or set Immersed cells/Coupling = "
                 "semi-implicit";
      }
    return "";
  }
} // namespace rbc_ifem

#ifndef rbc_ifem_ifem_volume_watch_h
#define rbc_ifem_ifem_volume_watch_h

#include <string>
#include <vector>

namespace rbc_ifem
{
  /**
   * The cells' volume changes step by step, watched for the two signs of a
   * run gone wrong that no solver reports: a volume change beyond a bound
   * (the volume penalty holds a stable run's within a percent), and the
   * step-to-step oscillation of an unstable coupling, whose increments
   * alternate in sign and grow, step after step.
   */
  class VolumeWatch
  {
  public:
    /// A watch of @p n_cells cells that flags a volume change beyond
    /// @p bound (a fraction of the reference volume).
    VolumeWatch(const unsigned int n_cells, const double bound);

    /**
     * Add each cell's volume change (V/V0 - 1) of the step just made;
     * returns why the run should stop, or "" if nothing is wrong.
     */
    std::string
    add(const std::vector<double> &volume_changes);

    /// Increments of the volume change below this are round-off.
    static constexpr double smallest_increment = 1e-4;
    /// This many growing, sign-alternating increments in a row are an
    /// instability.
    static constexpr unsigned int oscillating_steps = 6;

  private:
    const double        bound;
    std::vector<double> last_change, last_increment;
    /// Per cell, how many steps in a row the increments alternate and grow.
    std::vector<unsigned int> growing;
  };
} // namespace rbc_ifem

#endif

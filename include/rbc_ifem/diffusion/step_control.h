#ifndef rbc_ifem_diffusion_step_control_h
#define rbc_ifem_diffusion_step_control_h

#include <vector>

namespace rbc_ifem
{
  /**
   * The steps of a BDF2 integration (CutCellOxygen::try_step()): fixed, or
   * chosen from each step's estimate of its local error.
   *
   * With a tolerance of zero every step is the first step given (shortened
   * only to land on a stop). Otherwise a step whose error is at most the
   * tolerance is accepted, a longer one is tried again shorter, and the
   * next step is h (0.9 tolerance/error)^⅓ (BDF2's local error goes as
   * h³), at most twice and at least a fifth of the last, and at most the
   * largest step.
   */
  class StepControl
  {
  public:
    /**
     * Steps from @p first_step [s], controlled to @p tolerance (zero:
     * fixed steps), none longer than @p largest_step.
     */
    StepControl(const double first_step,
                const double tolerance,
                const double largest_step);

    /// The step to try from @p time: the step, but ending at @p stop if it
    /// would pass it or end within a tenth of a step before it, and half
    /// the way there from within two steps of it.
    double
    next(const double time, const double stop) const;

    /**
     * Judge the step last tried by next() with the local error @p error
     * (the root mean square of the fields' relative errors): true if it is
     * accepted; either way the next step is chosen.
     */
    bool
    judge(const double error);

    /// How many steps were tried again shorter.
    unsigned int
    n_rejected() const;

  private:
    const double tolerance, largest_step;
    double       step;
    /// The last step next() gave, and whether it was cut to a stop.
    mutable double last_tried = 0.;
    mutable bool   cut        = false;
    unsigned int   rejected   = 0;
  };

  /**
   * The times a run of @p duration [s] stops at to write its outputs,
   * every @p period: the multiples of the period before the duration, and
   * the duration. A multiple within 1e-9 periods of the duration is the
   * duration itself, so that rounding in k × period leaves no sliver of a
   * step, and no second row at the same time, before the end.
   */
  std::vector<double>
  output_times(const double duration, const double period);
} // namespace rbc_ifem

#endif

// Variable-step BDF2 and its step control (include/rbc_ifem/diffusion/
// bdf2.h, step_control.h): the derivative is exact for quadratics and the
// extrapolation exact for them too, whatever the three steps; on a cubic
// Milne's estimate, factor × (BDF2's solution − the extrapolation), equals
// BDF2's local error exactly (both are h³ u‴ times constants); equal steps
// give 3/2, 2, 1/2 and the factor 2/11. StepControl lands on its stops
// (from two steps before, in two halves), keeps fixed steps
// that divide the way, grows the step by at most 2 after a small error and
// rejects a step whose error is above the tolerance, and a failed one at a
// fifth. output_times() ends on the duration without a sliver before it.

#include <rbc_ifem/diffusion/bdf2.h>
#include <rbc_ifem/diffusion/step_control.h>

#include "check.h"

#include <cmath>
#include <limits>
#include <vector>

using namespace rbc_ifem;

int
main()
{
  Checker check;

  // Equal steps: the textbook BDF2 and Milne's 2/11.
  const Bdf2 equal(0.1, 0.1);
  check.near("equal steps: sigma", equal.sigma, 1.5, 1e-15);
  check.near("equal steps: now", equal.now, 2., 1e-15);
  check.near("equal steps: before", equal.before, 0.5, 1e-15);
  check.near("equal steps: factor",
             Bdf2Error(0.1, 0.1, 0.1).factor,
             2. / 11.,
             1e-15);
  check.near("first step: BDF1", Bdf2(0.1, 0.).sigma, 1., 0.);
  check.near("step 3 times the last: BDF1", Bdf2(0.3, 0.1).sigma, 1., 0.);

  // Unequal steps h = 0.3, h₁ = 0.2, h₂ = 0.5 ending at t = 1.
  const double h = 0.3, h1 = 0.2, h2 = 0.5, t = 1.;
  const double times[4]  = {t, t - h, t - h - h1, t - h - h1 - h2};
  const auto   quadratic = [](const double s) { return 2. - s + 3. * s * s; };
  const Bdf2   bdf(h, h1);
  check.near("quadratic: BDF2's derivative",
             bdf.derivative(quadratic(times[0]),
                            quadratic(times[1]),
                            quadratic(times[2]),
                            h),
             -1. + 6. * t,
             1e-12);
  const Bdf2Error estimate(h, h1, h2);
  const auto      extrapolated = [&](const auto &u) {
    return estimate.current * u(times[1]) + estimate.last * u(times[2]) +
           estimate.before_last * u(times[3]);
  };
  check.near("quadratic: extrapolation",
             extrapolated(quadratic),
             quadratic(t),
             1e-12);

  // u' = u''' t³/6 with u = t³: BDF2's step from exact values solves
  // (σ uⁿ⁺¹ − now uⁿ + before uⁿ⁻¹)/h = 3t² exactly (f does not depend on
  // u), so its error is the local error and Milne's device must give it.
  const auto   cubic    = [](const double s) { return s * s * s; };
  const double solution = (h * 3. * t * t + bdf.now * cubic(times[1]) -
                           bdf.before * cubic(times[2])) /
                          bdf.sigma;
  check.near("cubic: Milne's estimate / the local error",
             estimate.factor * (solution - extrapolated(cubic)) /
               (solution - cubic(t)),
             1.,
             1e-10);

  // Fixed steps of 0.002 reach a stop at 0.01 in five equal steps.
  StepControl fixed(0.002, 0., 1.);
  double      time = 0.;
  for (unsigned int i = 0; i < 5; ++i)
    {
      const double step = fixed.next(time, 0.01);
      check.near("fixed: the step", step, 0.002, 0.);
      check.holds("fixed: accepted", fixed.judge(1.));
      time += step;
    }
  check.near("fixed: at the stop", time, 0.01, 1e-15);

  // Controlled: a small error doubles the step; one above the tolerance is
  // rejected and the step shortened; near a stop the last two steps split
  // the way.
  StepControl controlled(0.01, 1e-3, 1.);
  check.near("controlled: first", controlled.next(0., 10.), 0.01, 0.);
  check.holds("controlled: small error accepted", controlled.judge(1e-6));
  check.near("controlled: doubled", controlled.next(0.01, 10.), 0.02, 1e-15);
  check.holds("controlled: large error rejected", !controlled.judge(8e-3));
  check.near("controlled: shortened to 0.9 (1/8)^(1/3)",
             controlled.next(0.01, 10.),
             0.02 * 0.9 / 2.,
             1e-15);
  StepControl  near_stop(0.4, 1e-3, 1.);
  const double first  = near_stop.next(0., 0.7),
               second = near_stop.next(first, 0.7);
  check.near("near a stop: halves", first, 0.35, 1e-15);
  check.near("near a stop: lands", first + second, 0.7, 1e-15);

  // A failed step (infinite error) is tried again at a fifth.
  StepControl failing(0.01, 1e-3, 1.);
  failing.next(0., 10.);
  check.holds("failed: rejected",
              !failing.judge(std::numeric_limits<double>::infinity()));
  check.near("failed: a fifth", failing.next(0., 10.), 0.002, 1e-15);

  // The outputs of 0.3 s every three steps of 0.3/45 s (Duration 0.3,
  // Time step 0.0067, Output interval 0.02): 15, the last the duration
  // itself, though 15 periods round below it (no sliver of a step before
  // the end, no second row at 0.3).
  const double period = 0.3 / 45 * 3;
  check.holds("outputs: 15 periods below 0.3 in floating point",
              15 * period < 0.3);
  const std::vector<double> outputs = output_times(0.3, period);
  check.near("outputs: how many", outputs.size(), 15, 0);
  check.near("outputs: the last", outputs.back(), 0.3, 0.);
  check.near("outputs: the one before", outputs[13], 14 * period, 0.);
  check.near("outputs: 0.1 every 0.03", output_times(0.1, 0.03).size(), 4, 0);
  return check.exit_code();
}

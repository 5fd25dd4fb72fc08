#ifndef rbc_ifem_diffusion_bdf2_h
#define rbc_ifem_diffusion_bdf2_h

namespace rbc_ifem
{
  /**
   * The coefficients of BDF2 with a step Δt after a step Δt_old, ω =
   * Δt/Δt_old:
   *
   *   u'(tⁿ⁺¹) ≈ (sigma uⁿ⁺¹ − now uⁿ + before uⁿ⁻¹) / Δt,
   *
   * sigma = (1 + 2ω)/(1 + ω), now = 1 + ω, before = ω²/(1 + ω): second order
   * for any ω, 3/2, 2, 1/2 for equal steps. BDF1 (1, 1, 0) for the first
   * step (Δt_old = 0) and after a step more than 1 + √2 times the last,
   * beyond which variable-step BDF2 is not zero-stable.
   */
  struct Bdf2
  {
    Bdf2(const double step, const double old_step)
    {
      const double omega = old_step > 0. ? step / old_step : 0.;
      if (omega > 0. && omega <= 2.414)
        {
          sigma  = (1. + 2. * omega) / (1. + omega);
          now    = 1. + omega;
          before = omega * omega / (1. + omega);
          growth = omega;
        }
    }

    double sigma = 1., now = 1., before = 0.;
    /// ω; zero for BDF1. The fields extrapolated to tⁿ⁺¹ are
    /// (1 + growth) uⁿ − growth uⁿ⁻¹.
    double growth = 0.;

    /// The derivative at tⁿ⁺¹ of values @p next, @p current, @p last at
    /// tⁿ⁺¹, tⁿ, tⁿ⁻¹, a step @p step apart from the last.
    double
    derivative(const double next,
               const double current,
               const double last,
               const double step) const
    {
      return (sigma * next - now * current + before * last) / step;
    }
  };

  /**
   * The local error of a BDF2 step (Bdf2) of length h after steps h₁ and
   * h₂, by Milne's device: the quadratic through the last three fields,
   * extrapolated to tⁿ⁺¹, misses u by C_P h³ u‴, C_P = (1 + h₁/h)(1 +
   * (h₁ + h₂)/h)/6, and BDF2 by −C_B h³ u‴, C_B = (1 + ω)²/(6ω(1 + 2ω));
   * so the step's error is factor × (uⁿ⁺¹ − the extrapolation), factor =
   * C_B/(C_B + C_P) (2/11 for equal steps).
   */
  struct Bdf2Error
  {
    Bdf2Error(const double step, const double old_step, const double older_step)
    {
      const double h = step, h1 = old_step, h2 = older_step;
      current            = (h + h1) * (h + h1 + h2) / (h1 * (h1 + h2));
      last               = -h * (h + h1 + h2) / (h1 * h2);
      before_last        = h * (h + h1) / ((h1 + h2) * h2);
      const double omega = h / h1;
      const double c_b =
        (1. + omega) * (1. + omega) / (6. * omega * (1. + 2. * omega));
      const double c_p = (1. + h1 / h) * (1. + (h1 + h2) / h) / 6.;
      factor           = c_b / (c_b + c_p);
    }

    /// The extrapolation's weights of uⁿ, uⁿ⁻¹ and uⁿ⁻².
    double current, last, before_last;
    double factor;
  };
} // namespace rbc_ifem

#endif

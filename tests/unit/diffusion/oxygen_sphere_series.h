// Exact series (eigenfunction) solution of transient, linear, spherically
// symmetric O2 diffusion with hemoglobin binding: a sphere ("cytoplasm",
// 0 <= r < a) in a concentric shell ("plasma", a < r < b). Header-only, no
// deal.II. Checked against an independent Chebyshev/Radau solution by
// oxygen_sphere_series_check.py (agreement ~1e-11, ~1e-8 for DH = 0).
//
//   shell:  αp ∂t P = αp Dp ΔP
//   sphere: αc ∂t P = αc Dc ΔP − C q,  ∂t S = DH ΔS + q,  q = k (λP − S)
//   r = a:  P continuous, αp Dp ∂r P(a+) = αc Dc ∂r P(a−), ∂r S = 0
//   r = b:  P = P_A;   t = 0: P = P0, S = λ P0.
//
// Derivation (κ = αc Dc, K = αp Dp):
// 1. P = P_A, S = λ P_A satisfies every equation (q = 0, ΔP = ΔS = 0): it is
//    the steady state. The rest (u, v) = (P − P_A, S − λ P_A) solves the
//    homogeneous problem, u(b) = 0, (u, v)(0) = (P0 − P_A)(1, λ).
// 2. Multiplying the S equation by C/λ makes the problem symmetric: mass
//    diag(αc, C/λ) (αp in the shell), reaction Ck [[λ, −1], [−1, 1/λ]] (≥ 0),
//    fluxes κ∂r u, K∂r u, (C/λ) DH ∂r v. Modes (u, v) e^{−μt} have real μ > 0
//    and are orthogonal in  <f, g> = ∫sphere (αc fu gu + (C/λ) fv gv) dV
//    + ∫shell αp fu gu dV.
// 3. Sphere: (u, v) = Σi di (1, ρi) φ(xi, r), φ(x, r) = sin(√x r)/(√x r)
//    (sinh if x < 0; entire in x). The xi = βi² solve the 2×2 dispersion
//    relation (p − x)(s − x) = Ck²λ/(κ DH), p = (αc μ − Ckλ)/κ, s = (μ − k)/DH
//    (real and distinct for DH > 0), ρi = κ (xi − p)/(Ck) = kλ/(k − μ + DH xi).
//    Shell: u = E ψ, ψ = sin(γ(b − r))/(γ r), γ² = μ/Dp. DH = 0: one branch,
//    κ x = μ (αc + Ckλ/(k − μ)), ρ = kλ/(k − μ).
// 4. μ are the roots of H(μ) = Λsh(μ) − Λs(μ), Λ = interface flux (K∂r u,
//    resp. κ∂r u with ∂r v = 0) for u(a) = 1 (Dirichlet-to-Neumann maps).
//    Green's identity: dΛsh/dμ = αp∫shell u² dV/(4πa²) > 0 and dΛs/dμ =
//    −<u, u>sphere/(4πa²) < 0, so H increases strictly from −∞ to +∞ between
//    consecutive poles: EXACTLY ONE eigenvalue in each such gap, one in
//    (0, first pole) as H(0+) = Λsh(0) < 0. Poles: the shell's Dirichlet
//    eigenvalues Dp (nπ/(b − a))² and the poles of Λs, which interlace with
//    its zeros, the sphere's Neumann eigenvalues ∂r φ(xi, a) = 0 ⇔ xi(μ) =
//    (z/a)², tan z = z (explicit). Every root is found by bisection in a
//    bracket holding exactly one: none can be skipped.
//    DH = 0: the spectrum accumulates at μ = k from below (S modes with
//    nothing to smooth them). That branch is parametrised by β = √x (poles of
//    Λs at βa = jπ), the branch μ > k by μ.
// 5. cn = <w0, mn>/<mn, mn>, and <w0, mn> = (P0 − P_A) × (O2 content of mn).
//    The sphere integrals are closed forms (Green's identity for ∫φ1 φ2 r²).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

namespace oxygen_sphere_series
{
  struct Parameters
  {
    double a = 2., b = 6.;                 // radii [µm]
    double alpha_p = 2.82e-5, D_p = 2180.; // plasma
    double alpha_c = 3.38e-5, D_c = 950.;  // cytoplasm
    double C      = 0.455;                 // heme capacity
    double D_H    = 14.4;                  // hemoglobin diffusivity
    double k      = 44.;                   // binding rate [1/s]
    double lambda = 1. / 26.8;             // [1/Torr]
    double P0 = 0., P_A = 1.;              // [Torr]
  };

  struct State
  {
    double sphere_o2;     // ∫sphere (αc P + C S) dV  [µm³ O2]
    double shell_o2;      // ∫shell αp P dV
    double mean_S;        // volume mean of S over the sphere
    double mean_P_sphere; // volume mean of P over the sphere
  };

  struct Mode // one term of the remainder: cn e^{−μn t} (u, v)n
  {
    double mu, qP, qS,
      qShell; // cn ∫sphere u dV, cn ∫sphere v dV, cn ∫shell u dV
  };

  namespace detail
  {
    constexpr double pi = 3.14159265358979323846;

    // y = z² (z imaginary if y < 0): S = sin z/z = φ(a), J = (sin z − z cos z)
    // /z³ (∂r φ(a) = −x a J, ∫0^a φ r² dr = a³ J), G = ∫0^a φ² r² dr/a³ =
    // (1 − sin 2z/2z)/(2y). For y < −1, S and J carry the factor e^{−|z|}, G
    // e^{−2|z|} (no overflow); it is common to a branch and cancels throughout.
    struct Sph
    {
      double S, J, G;
    };
    inline Sph
    sph(const double y)
    {
      if (std::abs(y) <= 1.) // Taylor series in y
        {
          Sph    f{0., 0., 0.};
          double tS = 1., tJ = 1. / 3., tG = 1. / 3.;
          for (int m = 0; m < 20; ++m)
            {
              f.S += tS, f.J += tJ, f.G += tG;
              tS *= -y / ((2 * m + 2) * (2 * m + 3));
              tJ *= -y * (m + 2) / ((m + 1.) * (2 * m + 4) * (2 * m + 5));
              tG *= -4 * y / ((2 * m + 4) * (2 * m + 5));
            }
          return f;
        }
      if (y > 0)
        {
          const double z = std::sqrt(y), s = std::sin(z), c = std::cos(z);
          return {s / z, (s - z * c) / (y * z), (1 - s * c / z) / (2 * y)};
        }
      const double w = std::sqrt(-y), e = std::exp(-2 * w);
      return {(1 - e) / (2 * w),
              (w * (1 + e) - (1 - e)) / (2 * w * w * w),
              ((1 - e * e) / (4 * w) - e) / (2 * w * w)};
    }

    // Bisection for the − → + sign change of f inside the bracket (lo, hi).
    inline double
    bisect(const std::function<double(double)> &f, double lo, double hi)
    {
      for (double mid = 0.5 * (lo + hi); mid > lo && mid < hi;
           mid        = 0.5 * (lo + hi))
        (f(mid) < 0 ? lo : hi) = mid;
      return 0.5 * (lo + hi);
    }

    // Root z ∈ (mπ, (m + ½)π) of tan z = z, m ≥ 1.
    inline double
    tan_root(const int m)
    {
      const double sg =
        m % 2 ? -1. : 1.; // −sign of sin z − z cos z just above mπ
      return bisect(
        [sg](double z) { return sg * (std::sin(z) - z * std::cos(z)); },
        m * pi,
        (m + 0.5) * pi);
    }
  } // namespace detail

  class Series
  {
  public:
    // DH > 0: the n_modes smallest eigenvalues. DH = 0: n_modes eigenvalues
    // below k (where they accumulate) and n_modes above.
    Series(const Parameters &params, const unsigned int n_modes = 400)
      : p(params)
      , kappa(p.alpha_c * p.D_c)
      , K(p.alpha_p * p.D_p)
      , L(p.b - p.a)
      , Ckl(p.C * p.k * p.lambda)
    {
      if (!(p.a > 0 && p.b > p.a && p.alpha_p > 0 && p.D_p > 0 &&
            p.alpha_c > 0 && p.D_c > 0 && p.C > 0 && p.D_H >= 0 && p.k > 0 &&
            p.lambda > 0 && n_modes > 0))
        throw std::invalid_argument(
          "oxygen_sphere_series::Series: bad parameters");
      for (const Branches &sp :
           p.D_H > 0 ? roots_diffusive(n_modes) : roots_static(n_modes))
        modes_.push_back(mode(sp));
    }

    // P = P_A + Σ cn e^{−μn t} un etc.; t = 0 returns the initial state
    // exactly.
    State
    at(const double t) const
    {
      if (!(t >= 0))
        throw std::domain_error("oxygen_sphere_series::Series::at: t < 0");
      const double Vs = 4. / 3 * detail::pi * std::pow(p.a, 3),
                   Vl = 4. / 3 * detail::pi *
                        (std::pow(p.b, 3) - std::pow(p.a, 3)),
                   P = t == 0 ? p.P0 : p.P_A;
      State s{Vs * (p.alpha_c + p.C * p.lambda) * P,
              Vl * p.alpha_p * P,
              p.lambda * P,
              P};
      if (t == 0)
        return s;
      // DH = 0: v = v0 e^{−kt} + Σ cn vn (e^{−μn t} − e^{−kt}) (Duhamel for
      // ∂t v = k(λu − v)); the bracket ~ t/βn² for the modes piling up at
      // μ → k gives their tail two more orders of decay than the plain sum.
      const double ek = p.D_H == 0 ? std::exp(-p.k * t) : 0.,
                   v0 = p.lambda * (p.P0 - p.P_A);
      s.sphere_o2 += ek * p.C * v0 * Vs, s.mean_S += ek * v0;
      for (auto m = modes_.rbegin(); m != modes_.rend();
           ++m) // small terms first
        {
          const double e  = std::exp(-m->mu * t),
                       eS = p.D_H == 0 ? ek * std::expm1((p.k - m->mu) * t) : e;
          s.sphere_o2 += e * p.alpha_c * m->qP + eS * p.C * m->qS;
          s.shell_o2 += e * p.alpha_p * m->qShell;
          s.mean_S += eS * m->qS / Vs;
          s.mean_P_sphere += e * m->qP / Vs;
        }
      return s;
    }

    double
    steady_sphere_o2() const
    {
      return 4. / 3 * detail::pi * std::pow(p.a, 3) *
             (p.alpha_c + p.C * p.lambda) * p.P_A;
    }

    const std::vector<Mode> &
    modes() const
    {
      return modes_;
    } // increasing μ per branch

  private:
    const Parameters  p;
    const double      kappa, K, L, Ckl;
    std::vector<Mode> modes_;

    struct Branches // the sphere side at one μ: nb branches (x, ρ, φ data)
    {
      int         nb;
      double      mu, x[2], rho[2];
      detail::Sph f[2];
    };

    Branches
    one(const double mu, const double x, const double rho) const
    {
      return {1, mu, {x, 0.}, {rho, 0.}, {detail::sph(x * p.a * p.a), {}}};
    }

    // Item 3, cancellation-free: x1 > x2, x1 x2 = μ(αc(μ − k) − Ckλ)/(κ DH).
    Branches
    at_mu(const double mu) const
    {
      if (p.D_H == 0)
        return one(mu,
                   mu * (p.alpha_c + Ckl / (p.k - mu)) / kappa,
                   p.k * p.lambda / (p.k - mu));
      const double pp = (p.alpha_c * mu - Ckl) / kappa, s = (mu - p.k) / p.D_H,
                   off = Ckl * p.k / (kappa * p.D_H), h = 0.5 * (pp - s),
                   m = 0.5 * (pp + s), sq = std::sqrt(h * h + off),
                   prod = mu * (p.alpha_c * (mu - p.k) - Ckl) / (kappa * p.D_H),
                   d1   = h > 0 ? off / (h + sq) : sq - h,
                   d2   = h > 0 ? -(h + sq) : off / (h - sq); // xi − p
      Branches b{2,
                 mu,
                 {m >= 0 ? m + sq : prod / (m - sq),
                  m >= 0 ? prod / (m + sq) : m - sq},
                 {kappa * d1 / (p.C * p.k), kappa * d2 / (p.C * p.k)},
                 {}};
      for (int i = 0; i < 2; ++i)
        b.f[i] = detail::sph(b.x[i] * p.a * p.a);
      return b;
    }

    // DH = 0, μ < k, from x = β²: ε = k − μ > 0 solves αc ε² + (κx − αc k +
    // Ckλ) ε = Ck²λ.
    Branches
    at_x_lower(const double x) const
    {
      const double B   = kappa * x - p.alpha_c * p.k + Ckl,
                   q   = std::sqrt(B * B + 4 * p.alpha_c * Ckl * p.k),
                   eps = B > 0 ? 2 * Ckl * p.k / (B + q) :
                                 (q - B) / (2 * p.alpha_c);
      return one(p.k - eps, x, p.k * p.lambda / eps);
    }

    double
    dphi(const Branches &b, const int i) const
    {
      return -b.x[i] * p.a * b.f[i].J;
    } // ∂r φi(a)

    double
    lambda_shell(const double mu) const // K ψ'(a)/ψ(a)
    {
      const double g = std::sqrt(mu / p.D_p);
      return -K * (g / std::tan(g * L) + 1 / p.a);
    }
    double
    lambda_sphere(
      const Branches &b) const // κ ∂r u(a) for u(a) = 1 (and ∂r v(a) = 0)
    {
      if (b.nb == 1)
        return kappa * dphi(b, 0) / b.f[0].S;
      const double d1 = dphi(b, 0), d2 = dphi(b, 1);
      return kappa * d1 * d2 * (b.rho[1] - b.rho[0]) /
             (b.rho[1] * b.f[0].S * d2 - b.rho[0] * b.f[1].S * d1);
    }

    // One root of the increasing h in (lo, first pole) and in each gap between
    // poles.
    std::vector<double>
    roots_between(double                               lo,
                  std::vector<double>                  poles,
                  const std::function<double(double)> &h,
                  const unsigned                       n) const
    {
      std::sort(poles.begin(), poles.end());
      std::vector<double> r;
      for (auto q = poles.begin(); q != poles.end() && r.size() < n; ++q)
        if (*q > lo)
          r.push_back(detail::bisect(h, lo, *q)), lo = *q;
      return r;
    }
    std::vector<double>
    shell_poles(const double from, const double to) const
    {
      std::vector<double> v;
      const double        s1 =
        p.D_p * std::pow(detail::pi / L, 2); // Dp (nπ/L)² = n² s1
      for (double n = 1; n * n * s1 < to; ++n)
        if (n * n * s1 > from)
          v.push_back(n * n * s1);
      return v;
    }
    double
    H_mu(const double mu) const
    {
      return lambda_shell(mu) - lambda_sphere(at_mu(mu));
    }

    std::vector<Branches>
    roots_diffusive(const unsigned n) const
    {
      for (double mu_max = 1e4 * (p.D_p + p.D_c + p.D_H + p.k);; mu_max *= 4)
        {
          // Sphere Neumann eigenvalues: for X = (z/a)² the two μ of
          // αc (μ − (Ckλ + κX)/αc)(μ − k − DH X) = Ck²λ, covering (0, 2
          // mu_max).
          std::vector<double> neu;
          for (int m = 0;; ++m)
            {
              const double X  = m ? std::pow(detail::tan_root(m) / p.a, 2) : 0.,
                           P_ = (Ckl + kappa * X) / p.alpha_c,
                           Q  = p.k + p.D_H * X,
                           hi = 0.5 * (P_ + Q) +
                                std::sqrt(0.25 * (P_ - Q) * (P_ - Q) +
                                          Ckl * p.k / p.alpha_c),
                           lo =
                             X *
                             (Ckl * p.D_H + kappa * p.k + kappa * p.D_H * X) /
                             p.alpha_c / hi; // product/hi
              neu.push_back(lo), neu.push_back(hi);
              if (lo > 2 * mu_max)
                break;
            }
          std::sort(neu.begin(), neu.end());
          std::vector<double> poles = shell_poles(0., mu_max);
          for (size_t j = 1; j < neu.size() && neu[j - 1] < mu_max;
               ++j) // Λs: 0 ↘ −∞ | +∞ ↘ 0
            if (neu[j] > neu[j - 1])
              poles.push_back(detail::bisect(
                [this](double mu) { return lambda_sphere(at_mu(mu)); },
                neu[j - 1],
                neu[j]));
          const std::vector<double> r = roots_between(
            0., poles, [this](double mu) { return H_mu(mu); }, n);
          if (r.size() == n && r.back() < mu_max)
            {
              std::vector<Branches> b;
              for (const double mu : r)
                b.push_back(at_mu(mu));
              return b;
            }
        }
    }

    std::vector<Branches>
    roots_static(const unsigned n) const // DH = 0
    {
      std::vector<double>
        poles; // μ < k, in β: βa = jπ and the shell poles below k
      for (unsigned j = 1; j <= n + 1; ++j)
        poles.push_back(j * detail::pi / p.a);
      for (const double s : shell_poles(0., p.k))
        poles.push_back(std::sqrt(s * (p.alpha_c + Ckl / (p.k - s)) / kappa));
      std::vector<Branches> b;
      for (const double be : roots_between(
             0.,
             poles,
             [this](double be) {
               const Branches c = at_x_lower(be * be);
               return lambda_shell(c.mu) - lambda_sphere(c);
             },
             n))
        b.push_back(at_x_lower(be * be));
      for (double mu_max = 1e4 * (p.D_p + p.D_c + p.k);; mu_max *= 4) // μ > k
        {
          poles = shell_poles(p.k, mu_max);
          for (int j = 1; j == 1 || poles.back() < mu_max;
               ++j) // βa = jπ: upper root of αc μ² − Bμ + κXk
            {
              const double X = std::pow(j * detail::pi / p.a, 2),
                           B = kappa * X + p.alpha_c * p.k + Ckl;
              poles.push_back(
                (B + std::sqrt(B * B - 4 * p.alpha_c * kappa * X * p.k)) /
                (2 * p.alpha_c));
            }
          const std::vector<double> up = roots_between(
            p.k, poles, [this](double mu) { return H_mu(mu); }, n);
          if (up.size() == n && up.back() < mu_max)
            {
              for (const double mu : up)
                b.push_back(at_mu(mu));
              return b;
            }
        }
    }

    // Item 5: the mode at a root and its coefficient.
    Mode
    mode(const Branches &sp) const
    {
      const double a = p.a, g = std::sqrt(sp.mu / p.D_p), z = g * L,
                   psi  = std::sin(z) / (g * a),
                   dpsi = -(g * a * std::cos(z) + std::sin(z)) / (g * a * a);
      // Null vector (d1[, d2], E) of the matching conditions at r = a (rows:
      // continuity, flux, [∂r v = 0]), each row scaled to unit length; the
      // largest cross product of two rows (DH > 0); DH = 0: normal of the
      // longer row.
      double rows[3][3] = {
        {sp.f[0].S, sp.f[1].S, -psi},
        {a * dphi(sp, 0), a * dphi(sp, 1), -K / kappa * a * dpsi},
        {sp.rho[0] * a * dphi(sp, 0), sp.rho[1] * a * dphi(sp, 1), 0.}};
      double d[3] = {0., 0., 0.}, best = -1.;
      if (sp.nb == 1)
        for (int i = 0; i < 2; ++i)
          {
            const double *r = rows[i];
            if (const double nr = std::hypot(r[0], r[2]); nr > best)
              best = nr, d[0] = -r[2], d[2] = r[0];
          }
      else
        {
          for (auto &r : rows)
            {
              const double nr =
                std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
              for (double &e : r)
                e /= nr;
            }
          for (int i = 0; i < 3; ++i)
            {
              const double *A = rows[i], *B = rows[(i + 1) % 3];
              const double  c[3] = {A[1] * B[2] - A[2] * B[1],
                                    A[2] * B[0] - A[0] * B[2],
                                    A[0] * B[1] - A[1] * B[0]};
              if (const double nc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
                  nc > best)
                best = nc, d[0] = c[0], d[1] = c[1], d[2] = c[2];
            }
        }
      // 4π∫ r² dr integrals; sphere cross term ∫φi φj r² = a²(φi ∂rφj − φj
      // ∂rφi)(a)/(xi − xj).
      const double fp = 4 * detail::pi, a3 = a * a * a;
      double       qu = 0., qv = 0., uu = 0., vv = 0.;
      for (int i = 0; i < sp.nb; ++i)
        {
          qu += fp * a3 * d[i] * sp.f[i].J,
            qv += fp * a3 * d[i] * sp.rho[i] * sp.f[i].J;
          for (int j = 0; j < sp.nb; ++j)
            {
              const double I =
                i == j ?
                  a3 * sp.f[i].G :
                  a * a * (sp.f[i].S * dphi(sp, j) - sp.f[j].S * dphi(sp, i)) /
                    (sp.x[i] - sp.x[j]);
              uu += fp * d[i] * d[j] * I,
                vv += fp * d[i] * d[j] * sp.rho[i] * sp.rho[j] * I;
            }
        }
      const detail::Sph sh = detail::sph(
        z * z); // shell: ∫ψ r² = b L² (1 − cos z)/z² − L³ J, ∫ψ² r² = L³ G
      const double qs = fp * d[2] * L * L *
                        (2 * p.b * std::pow(std::sin(z / 2) / z, 2) - L * sh.J),
                   ss   = fp * d[2] * d[2] * L * L * L * sh.G,
                   norm = p.alpha_c * uu + p.C / p.lambda * vv + p.alpha_p * ss,
                   c    = (p.P0 - p.P_A) *
                       (p.alpha_c * qu + p.C * qv + p.alpha_p * qs) / norm;
      return {sp.mu, c * qu, c * qv, c * qs};
    }
  };
} // namespace oxygen_sphere_series

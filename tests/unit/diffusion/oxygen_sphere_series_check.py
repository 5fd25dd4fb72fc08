#!/usr/bin/env python3
"""Independent check of oxygen_sphere_series.h (exact eigenfunction series for
transient O2 diffusion + linear hemoglobin binding in a sphere inside a shell).

The same 1-D radial problem is solved numerically with w = r P, w_S = r S
(so that the spherical Laplacian becomes d²/dr²):

  sphere 0<r<a:  ∂t w  = Dc w'' − (Ck/αc)(λ w − w_S),  ∂t w_S = DH w_S'' + k(λ w − w_S)
  shell  a<r<b:  ∂t w  = Dp w''
  w(0) = w_S(0) = 0, w continuous at a,
  κ (w'(a−) − w(a)/a) = K (w'(a+) − w(a)/a)          (flux continuity),
  w_S'(a) = w_S(a)/a                                  (∂r S = 0; not if DH = 0),
  w(b) = b P_A;   w = r P0, w_S = r λ P0 at t = 0,

by Chebyshev collocation on each of the two intervals (boundary values
eliminated through the interface/boundary conditions) and scipy's stiff
implicit Radau integrator (rtol 1e-10). The O2 contents are Clenshaw–Curtis
integrals. Independent of the series: no eigenvalues, no closed forms.

Also compares the smallest eigenvalues of the collocation operator with the
series' μ (count check: no root skipped) and the series' convergence in
n_modes at t = 1e-3 s.

Run:  python3 oxygen_sphere_series_check.py   (needs g++, numpy, scipy).
Exit status non-zero if any series/numerical relative difference > 1e-6.
"""
import os
import subprocess
import sys

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError:  # e.g. a pyenv python without numpy: retry with the system one
    if sys.executable != "/usr/bin/python3" and os.path.exists("/usr/bin/python3"):
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    raise

HERE = os.path.dirname(os.path.abspath(__file__))
TIMES = [1e-3, 5e-3, 0.02, 0.05, 0.2, 1.0]
TOL = 1e-6

DEFAULT = dict(a=2., b=6., alpha_p=2.82e-5, D_p=2180., alpha_c=3.38e-5, D_c=950.,
               C=0.455, D_H=14.4, k=44., lam=1. / 26.8, P0=0., P_A=1.)
CASES = [("default", dict()), ("D_H=0", dict(D_H=0.)), ("k=1000", dict(k=1000.))]

DRIVER = r'''
#include "oxygen_sphere_series.h"
#include <cstdio>
#include <cstdlib>
using namespace oxygen_sphere_series;
int main(int argc, char **argv) {
  Parameters p;
  double *f[] = {&p.a, &p.b, &p.alpha_p, &p.D_p, &p.alpha_c, &p.D_c, &p.C, &p.D_H, &p.k,
                 &p.lambda, &p.P0, &p.P_A};
  for (int i = 0; i < 12; ++i) *f[i] = std::atof(argv[i + 1]);
  const unsigned n = std::atoi(argv[13]);
  Series s(p, n);
  std::printf("modes %zu\n", s.modes().size());
  for (const auto &m : s.modes()) std::printf("mu %.17g\n", m.mu);
  for (int i = 14; i < argc; ++i) {
    const double t = std::atof(argv[i]);
    const State st = s.at(t);
    std::printf("state %.17g %.17g %.17g %.17g %.17g\n", t, st.sphere_o2, st.shell_o2,
                st.mean_S, st.mean_P_sphere);
  }
}
'''


def build_driver():
    src, exe = "/tmp/oxygen_sphere_series_driver.cc", "/tmp/oxygen_sphere_series_driver"
    with open(src, "w") as f:
        f.write(DRIVER)
    subprocess.run(["g++", "-O2", "-std=c++17", "-I", HERE, src, "-o", exe], check=True)
    return exe


def run_series(exe, p, n_modes, times):
    args = [p[k] for k in ("a", "b", "alpha_p", "D_p", "alpha_c", "D_c", "C", "D_H", "k",
                           "lam", "P0", "P_A")]
    out = subprocess.run([exe] + ["%.17g" % v for v in args] + [str(n_modes)] +
                         ["%.17g" % t for t in times], check=True, capture_output=True,
                         text=True).stdout.split("\n")
    mus = np.array([float(l.split()[1]) for l in out if l.startswith("mu ")])
    states = {}
    for l in out:
        if l.startswith("state "):
            v = [float(x) for x in l.split()[1:]]
            states[v[0]] = np.array(v[1:])
    return mus, states


def cheb(N):
    """Trefethen's Chebyshev differentiation matrix on x_j = cos(jπ/N), j = 0..N."""
    x = np.cos(np.pi * np.arange(N + 1) / N)
    c = np.hstack([2., np.ones(N - 1), 2.]) * (-1) ** np.arange(N + 1)
    X = np.tile(x, (N + 1, 1)).T
    dX = X - X.T
    D = np.outer(c, 1. / c) / (dX + np.eye(N + 1))
    D -= np.diag(D.sum(axis=1))
    return x, D


def clenshaw_curtis(N):
    """Weights on x_j = cos(jπ/N) for ∫_{-1}^{1}."""
    theta = np.pi * np.arange(N + 1) / N
    w = np.zeros(N + 1)
    v = np.ones(N - 1)
    if N % 2 == 0:
        w[0] = w[N] = 1. / (N * N - 1)
        for k in range(1, N // 2):
            v -= 2 * np.cos(2 * k * theta[1:-1]) / (4 * k * k - 1)
        v -= np.cos(N * theta[1:-1]) / (N * N - 1)
    else:
        w[0] = w[N] = 1. / (N * N)
        for k in range(1, (N - 1) // 2 + 1):
            v -= 2 * np.cos(2 * k * theta[1:-1]) / (4 * k * k - 1)
    w[1:-1] = 2 * v / N
    return w


class Collocation:
    """Linear ODE dy/dt = A y + f for the interior nodal values, full = T y + t0."""

    def __init__(self, p, N1, N2):
        a, b, L = p["a"], p["b"], p["b"] - p["a"]
        self.p = p
        kap, K = p["alpha_c"] * p["D_c"], p["alpha_p"] * p["D_p"]
        x1, D1 = cheb(N1)
        x2, D2 = cheb(N2)
        r1 = a * (1 + x1) / 2            # sphere: j = 0 at r = a, j = N1 at r = 0
        Ds1 = D1 * 2 / a
        r2 = a + L * (1 + x2) / 2        # shell:  j = 0 at r = b, j = N2 at r = a
        Ds2 = D2 * 2 / L
        diffuse_S = p["D_H"] > 0
        # full vector: [wP sphere (N1+1), wS sphere (N1+1), w shell (N2+1)]
        n1, n2 = N1 + 1, N2 + 1
        iP = np.arange(n1)
        iS = n1 + np.arange(n1)
        iL = 2 * n1 + np.arange(n2)
        nf = 2 * n1 + n2
        unknown = list(iP[1:N1]) + (list(iS[1:N1]) if diffuse_S else list(iS[0:N1])) + list(iL[1:N2])
        ny = len(unknown)
        T = np.zeros((nf, ny))
        t0 = np.zeros(nf)
        for c, i in enumerate(unknown):
            T[i, c] = 1.
        t0[iL[0]] = b * p["P_A"]           # w(b) = b P_A ; w(0) = wS(0) = 0 (rows stay zero)
        # interface: wP(a) = w_shell(a) =: wa (and wS(a) =: wsa if DH > 0)
        # flux: κ (Ds1[0]·wP − wa/a) − K (Ds2[N2]·wL − wa/a) = 0, linear in (y, wa)
        # Neumann for S: Ds1[0]·wS − wsa/a = 0
        def row_flux():
            g = np.zeros(nf)
            g[iP] += kap * Ds1[0]
            g[iL] -= K * Ds2[N2]
            g[iP[0]] -= kap / a
            g[iL[N2]] += K / a
            return g
        cons = [row_flux()]
        bvars = [[iP[0], iL[N2]]]          # wa appears in both places
        if diffuse_S:
            g = np.zeros(nf)
            g[iS] += Ds1[0]
            g[iS[0]] -= 1. / a
            cons.append(g)
            bvars.append([iS[0]])
        # constraint_j(full) = 0 with full = T y + t0 + Σ_m B_m z_m
        B = np.zeros((nf, len(bvars)))
        for m, idx in enumerate(bvars):
            B[idx, m] = 1.
        G = np.array(cons)
        M = G @ B
        Z = -np.linalg.solve(M, G @ T)
        z0 = -np.linalg.solve(M, G @ t0)
        T = T + B @ Z
        t0 = t0 + B @ z0
        # operator rows (full → d/dt) at the unknown nodes
        Op = np.zeros((nf, nf))
        D2s = Ds1 @ Ds1
        D2l = Ds2 @ Ds2
        Ck, lam = p["C"] * p["k"], p["lam"]
        Op[np.ix_(iP, iP)] = p["D_c"] * D2s - Ck * lam / p["alpha_c"] * np.eye(n1)
        Op[np.ix_(iP, iS)] = Ck / p["alpha_c"] * np.eye(n1)
        Op[np.ix_(iS, iS)] = p["D_H"] * D2s - p["k"] * np.eye(n1)
        Op[np.ix_(iS, iP)] = p["k"] * lam * np.eye(n1)
        Op[np.ix_(iL, iL)] = p["D_p"] * D2l
        Opu = Op[unknown]
        self.A = Opu @ T
        self.f = Opu @ t0
        self.T, self.t0 = T, t0
        self.y0 = np.concatenate([r1, lam * r1, r2])[unknown] * p["P0"]
        # quadrature: ∫ g(r) r dr (times the w-values) for the O2 integrals
        w1 = clenshaw_curtis(N1) * a / 2
        w2 = clenshaw_curtis(N2) * L / 2
        self.q = np.zeros((4, nf))
        fp = 4 * np.pi
        self.q[0, iP] = fp * p["alpha_c"] * w1 * r1
        self.q[0, iS] = fp * p["C"] * w1 * r1
        self.q[1, iL] = fp * p["alpha_p"] * w2 * r2
        self.q[2, iS] = 3. / a ** 3 * w1 * r1
        self.q[3, iP] = 3. / a ** 3 * w1 * r1

    def eigenvalues(self):
        ev = np.linalg.eigvals(self.A)
        return np.sort(-ev.real)

    def solve(self, times):
        sol = solve_ivp(lambda t, y: self.A @ y + self.f, (0., max(times)), self.y0,
                        method="Radau", t_eval=times, rtol=1e-10, atol=1e-14,
                        jac=self.A, dense_output=False)
        assert sol.success, sol.message
        full = self.T @ sol.y + self.t0[:, None]
        return {t: self.q @ full[:, i] for i, t in enumerate(sol.t)}


def main():
    exe = build_driver()
    names = ["sphere_o2", "shell_o2", "mean_S", "mean_P_sph", "uptake"]
    worst = 0.
    for label, over in CASES:
        p = dict(DEFAULT, **over)
        mus, ser = run_series(exe, p, 400, TIMES + [0.])
        # collocation at two resolutions: the finer is the reference, the
        # difference estimates its own error
        Ns = [(56, 56), (80, 72)] if p["k"] < 500 else [(80, 64), (112, 80)]
        num = []
        for N1, N2 in Ns:
            col = Collocation(p, N1, N2)
            num.append(col.solve(TIMES))
        ev = col.eigenvalues()
        print("\n=== case %s: D_H=%g k=%g  (series: %d modes; collocation N=%s and %s)" %
              (label, p["D_H"], p["k"], len(mus), Ns[0], Ns[1]))
        # eigenvalue count check: all series μ below a cut vs collocation
        # (cut midway between two series eigenvalues; for DH = 0 the branch
        # below k, where the eigenvalues accumulate, is compared up to 0.9 k
        # plus the 10 lowest above k)
        smu = np.sort(mus)
        j = np.searchsorted(smu, 2e4 if p["D_H"] > 0 else 0.9 * p["k"])
        cut = 0.5 * (smu[j - 1] + smu[j])
        sm, cm = smu[smu < cut], ev[ev < cut]
        if p["D_H"] == 0:
            up = smu[smu > p["k"]][:11]
            sm = np.concatenate([sm, up[:10]])
            cm = np.concatenate([cm, ev[(ev > p["k"]) & (ev < 0.5 * (up[9] + up[10]))]])
        n = min(len(sm), len(cm))
        err = np.abs(sm[:n] - cm[:n])
        rel = err / sm[:n]
        print("eigenvalues compared: %d series vs %d collocation, max rel diff %.2e" %
              (len(sm), len(cm), rel.max()))
        print("  smallest mu [1/s]:", " ".join("%.10g" % m for m in smu[:6]))
        # (collocation eigenvalues carry an absolute rounding error ~ |A| eps)
        if len(sm) != len(cm) or np.any(err > 1e-6 * sm[:n] + 1e-6):
            print("  EIGENVALUE MISMATCH"); worst = max(worst, 1.)
        init = ser[0.]
        print("%-9s %-10s %22s %22s %10s %10s" % ("t [s]", "quantity", "series", "numerical",
                                                  "rel diff", "num err"))
        for t in TIMES:
            s = np.append(ser[t], ser[t][0] - init[0])
            nf, nc = (np.append(x[t], x[t][0] - init[0]) for x in (num[1], num[0]))
            for j, name in enumerate(names):
                d = abs(s[j] - nf[j]) / abs(nf[j])
                e = abs(nf[j] - nc[j]) / abs(nf[j])
                worst = max(worst, d)
                flag = "  <-- FAIL" if d > TOL else ""
                print("%-9g %-10s %22.15e %22.15e %10.2e %10.2e%s" % (t, name, s[j], nf[j], d, e, flag))
        # series convergence in n_modes at t = 1e-3
        t = 1e-3
        ref = run_series(exe, p, 1600, [t])[1][t]
        print("series convergence at t = 1e-3 s (max rel diff to 1600 modes, uptake included):")
        for nm in (5, 10, 15, 20, 30, 40, 60, 80, 120, 200, 400):
            s = run_series(exe, p, nm, [t])[1][t]
            d = np.max(np.abs(s - ref) / np.abs(ref))
            print("  n_modes %4d: %.2e" % (nm, d))
    print("\nworst series/numerical relative difference: %.2e (tolerance %.0e)" % (worst, TOL))
    return 0 if worst <= TOL else 1


if __name__ == "__main__":
    sys.exit(main())

#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/membrane/membrane_equilibrium.h>

#include <cmath>
#include <deque>
#include <string>

namespace rbc_ifem
{
  namespace
  {
    /// Π(x) = E(x) + U(x), and its gradient -(F(x) + F_U(x)).
    double
    potential(const Membrane          &membrane,
              const ExternalPotential &external,
              const Vector<double>    &x,
              Vector<double>          &gradient,
              MembraneEnergy          &energy)
    {
      energy         = membrane.energy_and_forces(x, gradient);
      const double u = external(x, gradient);
      gradient *= -1.;
      return energy.total() + u;
    }

    /// The largest |g| over the nodes (x, y, z of a node together).
    double
    largest_nodal_force(const Membrane &membrane, const Vector<double> &g)
    {
      double largest = 0.;
      for (const auto &dofs : membrane.nodes())
        largest =
          std::max(largest,
                   std::sqrt(g[dofs[0]] * g[dofs[0]] + g[dofs[1]] * g[dofs[1]] +
                             g[dofs[2]] * g[dofs[2]]));
      return largest;
    }

    /// The L-BFGS memory: the last steps s and gradient changes y.
    using History = std::deque<std::pair<Vector<double>, Vector<double>>>;

    /// d = -H g by the two-loop recursion, H0 = (s·y / y·y) I.
    void
    quasi_newton_direction(const History        &history,
                           const Vector<double> &g,
                           Vector<double>       &d)
    {
      d = g;
      std::vector<double> alpha(history.size());
      for (int k = history.size() - 1; k >= 0; --k)
        {
          const auto &[s, y] = history[k];
          alpha[k]           = (s * d) / (y * s);
          d.add(-alpha[k], y);
        }
      if (!history.empty())
        d *= (history.back().first * history.back().second) /
             (history.back().second * history.back().second);
      for (unsigned int k = 0; k < history.size(); ++k)
        {
          const auto &[s, y] = history[k];
          d.add(alpha[k] - (y * d) / (y * s), s);
        }
      d *= -1.;
    }

    /**
     * Backtracking from the full step along d until Π falls enough
     * (Armijo). Near the solution the decrease of Π drops below its
     * round-off, so a step is accepted also when Π does not rise beyond
     * round-off and the slope along d has not turned steeply uphill (the
     * approximate Wolfe condition of Hager and Zhang, SIAM J. Optim. 16,
     * 2005). A step that inverts an element gives a non-finite Π and is
     * halved like any other. Returns false if 40 halvings found no step.
     */
    bool
    line_search(const Membrane          &membrane,
                const ExternalPotential &f,
                const Vector<double>    &x,
                const double             pi,
                const Vector<double>    &g,
                const Vector<double>    &d,
                Vector<double>          &trial,
                double                  &pi_trial,
                Vector<double>          &g_trial,
                MembraneEnergy          &energy)
    {
      const double slope = g * d;
      double       step  = 1.;
      for (unsigned int halvings = 0; halvings <= 40; ++halvings, step *= 0.5)
        {
          trial = x;
          trial.add(step, d);
          pi_trial          = potential(membrane, f, trial, g_trial, energy);
          const bool armijo = pi_trial <= pi + 1e-4 * step * slope;
          const bool approximate_wolfe =
            pi_trial <= pi + 1e-12 * std::abs(pi) &&
            g_trial * d <= -0.8 * slope;
          if (std::isfinite(pi_trial) && (armijo || approximate_wolfe))
            return true;
        }
      return false;
    }
  } // namespace

  EquilibriumReport
  find_equilibrium(const Membrane       &membrane,
                   const Vector<double> &external_forces,
                   Vector<double>       &x,
                   const double          tolerance,
                   const unsigned int    max_iterations)
  {
    // Fixed forces f: U(x) = -f·x.
    return find_equilibrium(
      membrane,
      [&external_forces](const Vector<double> &x, Vector<double> &forces) {
        forces += external_forces;
        return -(external_forces * x);
      },
      x,
      tolerance,
      max_iterations);
  }

  EquilibriumReport
  find_equilibrium(const Membrane          &membrane,
                   const ExternalPotential &f,
                   Vector<double>          &x,
                   const double             tolerance,
                   const unsigned int       max_iterations)
  {
    constexpr unsigned int memory = 20;
    EquilibriumReport      report;
    Vector<double> g(x.size()), trial(x.size()), g_trial(x.size()), d(x.size());
    double         pi = potential(membrane, f, x, g, report.energy);
    History        history;

    for (report.iterations = 0; report.iterations < max_iterations;
         ++report.iterations)
      {
        report.residual = largest_nodal_force(membrane, g);
        if (report.residual < tolerance)
          return report;

        // The quasi-Newton step; if it is no descent direction or the line
        // search finds nothing along it (a stale memory on a very
        // ill-conditioned energy), the memory starts anew from a short
        // steepest-descent step.
        quasi_newton_direction(history, g, d);
        double         pi_trial = 0.;
        MembraneEnergy energy;
        if (!(d * g < 0.) ||
            !line_search(
              membrane, f, x, pi, g, d, trial, pi_trial, g_trial, energy))
          {
            history.clear();
            d = g;
            d *= -1e-3 / std::max(1., report.residual);
            if (!line_search(
                  membrane, f, x, pi, g, d, trial, pi_trial, g_trial, energy))
              throw SolverFailure(
                "membrane equilibrium: the line search found no "
                "decrease of the energy (largest nodal residual " +
                std::to_string(report.residual) +
                " pN). Is Residual tolerance below round-off?");
          }

        Vector<double> s(trial), y(g_trial);
        s -= x;
        y -= g;
        if (s * y > 1e-14 * s.l2_norm() * y.l2_norm())
          {
            history.emplace_back(s, y);
            if (history.size() > memory)
              history.pop_front();
          }
        x.swap(trial);
        g.swap(g_trial);
        pi            = pi_trial;
        report.energy = energy;
      }
    throw SolverFailure("membrane equilibrium: not converged in " +
                        std::to_string(max_iterations) +
                        " L-BFGS iterations (largest nodal "
                        "residual " +
                        std::to_string(report.residual) + " pN, wanted " +
                        std::to_string(tolerance) +
                        " pN). Raise Stretching/Max iterations.");
  }
} // namespace rbc_ifem

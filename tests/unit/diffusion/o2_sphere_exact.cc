// O2 transport with hemoglobin binding (CutCellOxygen) against the exact
// series solution of a sphere of cytoplasm (radius a) in a ball of plasma
// (radius b) held at P_A on its surface, from P = P0 and S = λ P0 at t = 0:
//
//   α_p ∂P/∂t = α_p D_p ∇²P                 in the plasma,
//   α_c ∂P/∂t = α_c D_c ∇²P − C q,  ∂S/∂t = D_H ∇²S + q   in the cell,
//
// with the linear binding q = k (λ P − S), P and the flux continuous at
// r = a, ∂S/∂r = 0 there. The series (oxygen_sphere_series.h, checked
// against an independent radial solve by oxygen_sphere_series_check.py)
// gives the O2 taken up by the cell by time T. The program checks
// - the uptake's error on two meshes, with a binding slow enough that its
//   boundary layer inside the membrane is resolved (the order, about 0.7,
//   is printed: the lumped capacities and binding on cut cells are first
//   order there; doc/oxygen.md);
// - the order in time on one mesh, from the differences of three step
//   sizes halved in turn (the default binding rate);
// - the O2 balance of every step: the O2 in the ball changes by what
//   entered through its surface, to 1e-6;
// - equilibrium: with Hill binding and P_A = P_v, nothing changes;
// - fast binding (k × 1e5): S = λ P, the local equilibrium, to 1e-4.

#include <rbc_ifem/diffusion/cut_cell_oxygen.h>

#include "check.h"
#include "oxygen_sphere_series.h"

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>

#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

using namespace rbc_ifem;

namespace
{
  const oxygen_sphere_series::Parameters defaults;
  const double                           a = defaults.a, b = defaults.b;

  /// q = k (λ P − S).
  class LinearBinding : public OxygenBinding
  {
  public:
    LinearBinding(const double k, const double lambda)
      : k(k)
      , lambda(lambda)
    {}

    BindingRate
    rate(const double P, const double S) const override
    {
      return {k * (lambda * P - S), k * lambda, -k};
    }

    double
    equilibrium_saturation(const double P) const override
    {
      return lambda * P;
    }

  private:
    const double k, lambda;
  };

  /// The meshes of level @p level: the ball and the cell's membrane.
  struct Meshes
  {
    explicit Meshes(const unsigned int level)
      : ball(MPI_COMM_WORLD)
    {
      GridGenerator::hyper_sphere(membrane, Point<3>(), a);
      membrane.refine_global(level + 3);
      GridGenerator::hyper_ball_balanced(ball, Point<3>(), b);
      ball.refine_global(level + 1);
    }

    Triangulation<2, 3>                membrane;
    parallel::shared::Triangulation<3> ball;
  };

  /// The O2 parameters of the exact solution, P_A and P_v as given.
  OxygenParameters
  oxygen_parameters(const double alveolar, const double venous)
  {
    const oxygen_sphere_series::Parameters &p = defaults;
    OxygenParameters                        oxygen;
    oxygen.alveolar_pressure      = alveolar;
    oxygen.venous_pressure        = venous;
    oxygen.plasma_solubility      = p.alpha_p;
    oxygen.plasma_diffusivity     = p.D_p;
    oxygen.cytoplasm_solubility   = p.alpha_c;
    oxygen.cytoplasm_diffusivity  = p.D_c;
    oxygen.heme_capacity          = p.C;
    oxygen.hemoglobin_diffusivity = p.D_H;
    return oxygen;
  }

  struct Run
  {
    double uptake;        ///< the cell's O2 at the end less at the start
    double worst_balance; ///< the largest relative O2 imbalance
    CutCellOxygen::CellState start, end;
    unsigned long            n_dofs;
  };

  /// @p n_steps steps of @p time_step on @p meshes.
  Run
  transient(const Meshes           &meshes,
            const OxygenParameters &oxygen,
            const OxygenBinding    &binding,
            const double            time_step,
            const unsigned int      n_steps)
  {
    TimerOutput              timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    const MappingQ<2, 3>     membrane_mapping(2);
    const MembraneSurfaces   membranes({&meshes.membrane}, membrane_mapping);
    CutCellGeometry::Options options;
    options.refine_ridges    = false; // the sphere's centre is a ridge
    options.separate_insides = true;
    DiffusionParameters parameters;
    parameters.degree           = 2;
    parameters.linear_tolerance = 1e-11;
    const CutCellGeometry geometry(
      meshes.ball,
      membranes,
      std::make_shared<MembraneDistance>(membranes.meshes(), membrane_mapping),
      parameters.degree,
      std::nullopt,
      options,
      timer);
    CutCellOxygen o2(geometry, parameters, oxygen, binding, 0, timer);
    o2.assemble();
    o2.start(oxygen.venous_pressure);
    const CutCellOxygen::Amounts amounts = o2.amounts();
    const double start_total             = amounts.dissolved + amounts.bound;
    Run          run{0., 0., o2.cell_states()[0], {}, o2.n_dofs()};
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        o2.advance(time_step);
        const CutCellOxygen::Amounts now = o2.amounts();
        const double change = now.dissolved + now.bound - start_total;
        const double wall   = o2.wall_oxygen();
        if (wall != 0.)
          run.worst_balance =
            std::max(run.worst_balance,
                     std::abs(change - wall) / std::abs(wall));
      }
    run.end    = o2.cell_states()[0];
    run.uptake = run.end.oxygen - run.start.oxygen;
    return run;
  }
} // namespace

/// The O2 the cell takes up by @p end_time in @p n_steps, exact and on
/// mesh @p level, with the binding rate @p k.
std::pair<double, Run>
uptake(const double       k,
       const double       end_time,
       const unsigned int n_steps,
       const Meshes      &meshes)
{
  oxygen_sphere_series::Parameters p = defaults;
  p.k                                = k;
  const oxygen_sphere_series::Series series(p);
  const LinearBinding                binding(k, p.lambda);
  return {series.at(end_time).sphere_o2 - series.at(0.).sphere_o2,
          transient(meshes,
                    oxygen_parameters(p.P_A, p.P0),
                    binding,
                    end_time / n_steps,
                    n_steps)};
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;
  const Meshes                     coarse(0), fine(1);

  // Space: a binding slow enough (k = 0.5 s⁻¹) that its layer inside the
  // membrane, 1/m = (α_cD_c/(C λ k))^½ = 1.9 µm, is resolved on both
  // meshes; 10 steps leave a time error below 1e-5 of the uptake.
  std::vector<double> errors;
  for (const Meshes *meshes : {&coarse, &fine})
    {
      const auto [exact, run] = uptake(0.5, 0.2, 10, *meshes);
      errors.push_back(std::abs(run.uptake - exact) / exact);
      std::cout << "k = 0.5 /s, t = 0.2 s: " << run.n_dofs << " DoFs, uptake "
                << run.uptake << ", exact " << exact << ", relative error "
                << errors.back() << ", worst O2 balance " << run.worst_balance
                << '\n';
      check.at_most("O2 balance, " + std::to_string(run.n_dofs) + " DoFs",
                    run.worst_balance,
                    1e-6);
    }
  std::cout << "  observed order in space: " << std::log2(errors[0] / errors[1])
            << '\n';
  check.at_most("relative uptake error on the finer mesh", errors[1], 5e-3);
  check.at_least("error ratio, coarse / fine mesh", errors[0] / errors[1], 1.5);

  // Time: the default binding (k = 44 s⁻¹), 5, 10 and 20 steps.
  std::vector<double> uptakes;
  for (const unsigned int n_steps : {5u, 10u, 20u})
    uptakes.push_back(uptake(defaults.k, 0.02, n_steps, coarse).second.uptake);
  const double time_order = std::log2(std::abs(uptakes[0] - uptakes[1]) /
                                      std::abs(uptakes[1] - uptakes[2]));
  std::cout << "k = 44 /s, t = 0.02 s: uptakes with 5, 10, 20 steps "
            << uptakes[0] << ", " << uptakes[1] << ", " << uptakes[2]
            << "; observed order in time " << time_order << '\n';
  check.at_least("observed order in time", time_order, 1.8);

  // Equilibrium: Hill binding at P_A = P_v leaves everything as it was.
  const Run still = transient(
    coarse, oxygen_parameters(40., 40.), OxygenParameters().binding(), 0.01, 3);
  std::cout << "equilibrium at 40 Torr: S " << still.start.saturation << " → "
            << still.end.saturation << ", P " << still.start.pressure << " → "
            << still.end.pressure << '\n';
  check.near("equilibrium: S unchanged",
             still.end.saturation,
             still.start.saturation,
             1e-10);
  check.near("equilibrium: P unchanged", still.end.pressure, 40., 1e-8);

  // Fast binding (k × 1e5): S = λ P wherever P is, but for the lag S'/k,
  // about 1e-5 of S here.
  const Run quick = uptake(1e5 * defaults.k, 0.02, 10, coarse).second;
  std::cout << "fast binding: mean S " << quick.end.saturation
            << ", λ × mean P " << defaults.lambda * quick.end.pressure << '\n';
  check.near("fast binding: mean S / (λ mean P)",
             quick.end.saturation / (defaults.lambda * quick.end.pressure),
             1.,
             1e-4);
  return check.exit_code();
}

// Finite CO uptake (CutCellDiffusion::react_inside_cells()) against the exact
// solution of a spherical cell of radius a in a ball of radius b held at
// P_A: -∇·(κ_p ∇P) = 0 in the plasma (a < r < b), -∇·(κ_c ∇P) + k P = 0 in
// the cell, P and κ ∂P/∂r continuous at r = a. Inside P = C sinh(m r)/r with
// m² = k/κ_c, outside P = A + B/r; the uptake is P_A over two resistances
// in series,
//
//   DL = 1 / (R_p + R_c),  R_p = (1/a - 1/b) / (4π κ_p),
//   R_c = 1 / (4π κ_c a (m a coth(m a) - 1)),
//
// the plasma's (R_p = 1/DM of the membrane sink) and the cell's. As k → ∞,
// R_c → 0 and DL → DM; as k → 0, R_c → 1/(k V) and DL → k V, V the cell's
// volume. The program checks the order of the DL error on three meshes
// (from the first to the last and between the last two),
// conservation (the flow out of the P_A boundary equals the flow into the
// cell), and both limits on one mesh against the solver's own membrane sink
// and k V.

#include <rbc_ifem/diffusion/cut_cell_diffusion.h>
#include <rbc_ifem/diffusion/cut_cell_reaction.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include "check.h"

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/grid/grid_generator.h>

#include <cmath>
#include <optional>
#include <vector>

using namespace rbc_ifem;

namespace
{
  const double a = 2., b = 6.; // µm

  struct Flows
  {
    double        membrane;
    double        boundary;
    unsigned long n_dofs;
    unsigned int  iterations;
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

  /// The uptake of the cell: with @p rate k, the reaction, otherwise the
  /// membrane sink.
  Flows
  solve(const Meshes                &meshes,
        const DiffusionParameters   &parameters,
        const double                 cell_permeability,
        const std::optional<double> &rate)
  {
    TimerOutput            timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    const MappingQ<2, 3>   membrane_mapping(2);
    const MembraneSurfaces membranes({&meshes.membrane}, membrane_mapping);
    const auto             permeability = [&](const unsigned int id) {
      return parameters.permeability(id);
    };
    CutCellGeometry::Options options;
    options.refine_ridges    = false; // the sphere's centre is a ridge
    options.separate_insides = rate.has_value();
    const CutCellGeometry geometry(
      meshes.ball,
      membranes,
      std::make_shared<MembraneDistance>(membranes.meshes(), membrane_mapping),
      parameters.degree,
      std::nullopt,
      options,
      timer);
    std::unique_ptr<CutCellProblem> diffusion;
    if (rate)
      diffusion = std::make_unique<CutCellReaction>(
        geometry, parameters, permeability, 0, cell_permeability, *rate, timer);
    else
      diffusion = std::make_unique<CutCellDiffusion>(
        geometry, parameters, permeability, 0, timer);
    diffusion->assemble();
    diffusion->solve();
    return {diffusion->total_flow(),
            diffusion->boundary_flow(),
            diffusion->n_dofs(),
            diffusion->n_iterations()};
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;

  DiffusionParameters parameters;
  parameters.method           = DiffusionMethod::cut_cell;
  parameters.degree           = 2;
  parameters.linear_tolerance = 1e-12;
  const double kappa_p        = parameters.permeability(Material::plasma);
  // A cytoplasm half as permeable as the plasma, and a reaction whose
  // boundary layer (1/m) is half the cell's radius: both resistances count.
  const double kappa_c = 0.5 * kappa_p;
  const double m       = 2. / a;
  const double k       = m * m * kappa_c;
  const double P_A     = parameters.alveolar_pressure;
  const double R_p     = (1. / a - 1. / b) / (4. * numbers::PI * kappa_p);
  const double R_c =
    1. / (4. * numbers::PI * kappa_c * a * (m * a / std::tanh(m * a) - 1.));
  const double exact = P_A / (R_p + R_c);
  std::cout << "Spherical cell with a reaction: k = " << k
            << " /(s Torr), m a = " << m * a << ", exact flow " << exact
            << " µm³/s (R_c / R_p = " << R_c / R_p << ")\n";

  std::vector<double> errors;
  const unsigned int  n_levels = 3;
  for (unsigned int level = 0; level < n_levels; ++level)
    {
      const Meshes meshes(level);
      const Flows  flows = solve(meshes, parameters, kappa_c, k);
      errors.push_back(std::abs(flows.membrane - exact) / exact);
      std::cout << "  level " << level << ": " << flows.n_dofs << " DoFs, "
                << flows.iterations << " iterations, flow " << flows.membrane
                << ", relative error " << errors.back() << ", boundary flow "
                << flows.boundary << '\n';
      if (level > 0)
        std::cout << "  observed order, level " << level << ": "
                  << std::log2(errors[level - 1] / errors[level]) << '\n';
      check.near("boundary flow / membrane flow, level " +
                   std::to_string(level),
                 flows.boundary / flows.membrane,
                 1.,
                 1e-6);
    }
  const unsigned int last = n_levels - 1;
  check.at_least("observed order, levels 0 to " + std::to_string(last),
                 std::log2(errors[0] / errors[last]) / last,
                 1.8);
  check.at_least("observed order, level " + std::to_string(last),
                 std::log2(errors[last - 1] / errors[last]),
                 1.8);
  check.at_most("relative flow error on the finest mesh", errors[last], 1e-4);

  // The limits, on the middle mesh.
  const Meshes meshes(1);
  const double sink = solve(meshes, parameters, kappa_c, {}).membrane;
  const double fast = solve(meshes, parameters, kappa_c, 1e8 * k).membrane;
  std::cout << "Fast reaction (k × 1e8): flow " << fast << ", membrane sink "
            << sink << ", exact sink " << P_A / R_p << '\n';
  check.near("fast reaction / membrane sink", fast / sink, 1., 1e-3);
  const double slow_rate = 1e-6 * k;
  const double volume    = 4. / 3. * numbers::PI * a * a * a;
  const double slow =
    solve(meshes, parameters, kappa_c, slow_rate).membrane / P_A;
  std::cout << "Slow reaction (k × 1e-6): DL " << slow << ", k V "
            << slow_rate * volume << '\n';
  check.near("slow reaction: DL / (k V)",
             slow / (slow_rate * volume),
             1.,
             1e-3);
  return check.exit_code();
}

// mpirun: 1 2

// The periodic capillary (FlowDrive::periodic_capillary): with the ends
// joined and the pressure gradient G = 8μū/R² as a body force, one
// backward Euler step of 1 s from rest is Hagen-Poiseuille flow of mean
// speed ū; seen from a frame moving with U_frame = 300 µm/s, shifted by
// -U_frame. Checked against the exact profile: the velocity, the flow rate
// (ū - U_frame)πR² (relative to ūπR²), the pressure drop G L and ‖∇·v‖, on
// the level-1 lumen mesh as it is and band-refined near x = 0 only, so that
// the two periodic ends are refined differently (where the hanging nodes
// of the band, wherever they are, cost the same accuracy as a band in the
// middle of the segment). Runs on 1 and 2 ranks (periodic_poiseuille_np1,
// _np2).

#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include "check.h"
#include "velocity_error.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/numerics/vector_tools.h>

#include <optional>

using namespace rbc_ifem;

namespace
{
  struct Errors
  {
    double velocity, flow_rate, pressure_drop, divergence;
  };

  /// The errors on the level-1 mesh, refined once within 1 µm of @p band.
  Errors
  solve(const std::string &name, const std::optional<Point<3>> &band)
  {
    GeometryParameters geometry;
    geometry.periodic = true;
    const double R = geometry.capillary_radius, L = geometry.capillary_length;
    FluidParameters f;
    f.linear_tolerance = 1e-10;
    f.frame_velocity   = 300.;
    const double u     = f.inlet_mean_speed;

    parallel::shared::Triangulation<3> triangulation(
      MPI_COMM_WORLD,
      Triangulation<3>::none,
      false,
      parallel::shared::Triangulation<3>::partition_metis);
    create_fluid_mesh(triangulation, geometry, 1);
    if (band)
      refine_near_points(triangulation, {*band}, 1., 1);
    TimerOutput  timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    FluidProblem fluid(
      triangulation, f, FlowDrive::periodic_capillary(f, geometry), 1., timer);
    fluid.setup();
    const StepReport   report = fluid.advance();
    const FlowMeasures m      = fluid.measure();

    const PoiseuilleFlow exact(u, f.frame_velocity, f.viscosity, geometry);
    // ‖v_exact‖ in the lab frame, sqrt(4ū²πR²L/3), is the scale.
    const double scale = std::sqrt(4. * u * u * numbers::PI * R * R * L / 3.);
    const double area  = numbers::PI * R * R;
    Errors       e;
    e.velocity = velocity_l2_error(fluid, exact) / scale;
    e.flow_rate =
      std::abs(m.flow_rate - (u - f.frame_velocity) * area) / (u * area);
    e.pressure_drop =
      std::abs(m.pressure_drop / (8. * f.viscosity * u * L / (R * R)) - 1.);
    e.divergence = m.divergence_l2 / scale;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << "  " << name << ", "
                << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
                << " rank(s), " << fluid.n_dofs() << " DoFs, "
                << report.linear_iterations
                << " FGMRES iterations: velocity L2 " << e.velocity
                << ", flow rate " << e.flow_rate << ", pressure drop "
                << e.pressure_drop << ", ‖∇·v‖/‖v‖ " << e.divergence << '\n';
    return e;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;
  std::cout << "periodic Poiseuille, relative errors:\n";

  const Errors uniform = solve("uniform", std::nullopt);
  check.at_most("uniform: velocity L2 error", uniform.velocity, 2e-3);
  check.at_most("uniform: flow rate error", uniform.flow_rate, 2e-3);
  check.at_most("uniform: pressure drop error", uniform.pressure_drop, 1e-12);
  check.at_most("uniform: ‖∇·v‖ / ‖v‖", uniform.divergence, 1e-9);

  const Errors at_end    = solve("band at one end", Point<3>(0.3, 0., 2.));
  const Errors in_middle = solve("band in the middle", Point<3>(10., 0., 2.));
  check.at_most("band at one end: velocity L2 error", at_end.velocity, 5e-3);
  check.at_most("band at one end: flow rate error", at_end.flow_rate, 2e-3);
  check.at_most("band at one end: pressure drop error",
                at_end.pressure_drop,
                1e-4);
  check.at_most("band at one end: ‖∇·v‖ / ‖v‖", at_end.divergence, 3e-3);
  check.at_most("band at one end against one in the middle: velocity error",
                at_end.velocity / in_middle.velocity,
                1.25);
  return check.exit_code();
}

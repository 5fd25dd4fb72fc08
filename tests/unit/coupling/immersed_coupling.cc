// mpirun: 1 2 3 4

// The immersed coupling (ImmersedCoupling) on the fluid's Q2-Q1 space, for
// the nodes of an Evans-Fung membrane in the capillary, on any number of
// ranks:
//
// - spreading keeps the total force and the total torque: the spread load
//   against the interpolated constant and rotation fields gives Σ F_I and
//   Σ x_I × F_I (Q2 on the Q2-mapped mesh holds both fields exactly);
// - spreading and interpolation are adjoint, ⟨spread F, v⟩ = Σ F_I · v_I,
//   for a random v that satisfies the fluid's constraints;
// - a force-free membrane in steady Poiseuille flow, moved by the
//   interpolated velocity, follows the tracers of the exact flow;
// - a point pushed out of the capillary is reported, not dropped;
// - on a fully distributed mesh, a membrane carried along the whole
//   capillary crosses the partitions: at every step each point is on
//   exactly one rank, and the spread force is the total force.

#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>
#include <rbc_ifem/membrane/membrane.h>

#include "check.h"

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/numerics/vector_tools.h>

#include <memory>
#include <random>

using namespace rbc_ifem;

namespace
{
  const GeometryParameters geometry; // R = 5 µm, L = 20 µm

  /// The fluid of the capillary at refinement 1 (Stokes, ū = 500 µm/s).
  struct Flow
  {
    explicit Flow(const double time_step)
      : triangulation(MPI_COMM_WORLD,
                      Triangulation<3>::none,
                      false,
                      parallel::shared::Triangulation<3>::partition_metis)
      , timer(MPI_COMM_WORLD,
              std::cout,
              TimerOutput::never,
              TimerOutput::wall_times)
    {
      create_fluid_mesh(triangulation, geometry, 1);
      FluidParameters f;
      f.linear_tolerance = 1e-10;
      fluid              = std::make_unique<FluidProblem>(
        triangulation, f, FlowDrive::capillary(f, geometry), time_step, timer);
      fluid->setup();
    }

    /// A zero vector of the velocity space.
    VelocityVector
    vector() const
    {
      VelocityVector v;
      fluid->initialize_velocity_vector(v);
      return v;
    }

    parallel::shared::Triangulation<3> triangulation;
    TimerOutput                        timer;
    std::unique_ptr<FluidProblem>      fluid;
  };

  /// The nodes of a 7.5 µm Evans-Fung cell at @p center, axis along the flow.
  std::vector<Point<3>>
  membrane_nodes(const Point<3> &center)
  {
    Triangulation<2, 3> surface;
    create_cell_surface(surface,
                        EvansFungShape(7.5),
                        CellPlacement{center, Tensor<1, 3>({1., 0., 0.})},
                        2);
    const Membrane        membrane(surface, MembraneParameters());
    const Vector<double> &X = membrane.reference_positions();
    std::vector<Point<3>> nodes;
    for (const auto &dofs : membrane.nodes())
      nodes.emplace_back(X[dofs[0]], X[dofs[1]], X[dofs[2]]);
    return nodes;
  }

  /// A velocity field u(x) as a Function.
  class VelocityField : public Function<3>
  {
  public:
    explicit VelocityField(
      const std::function<Tensor<1, 3>(const Point<3> &)> &u)
      : Function<3>(3)
      , u(u)
    {}

    double
    value(const Point<3> &p, const unsigned int component) const override
    {
      return u(p)[component];
    }

  private:
    const std::function<Tensor<1, 3>(const Point<3> &)> u;
  };

  /// u interpolated into the velocity space.
  VelocityVector
  interpolated_field(const Flow                                          &flow,
                     const std::function<Tensor<1, 3>(const Point<3> &)> &u)
  {
    VelocityVector v = flow.vector();
    VectorTools::interpolate(flow.fluid->get_mapping(),
                             flow.fluid->velocity_dof_handler(),
                             VelocityField(u),
                             v);
    return v;
  }

  /**
   * spread_squares(): with weights w_I (here F_I squared, entry by entry),
   * its entry J is Σ_I w_I · φ_J(x_I)², where φ_J(x_I) is what interpolate()
   * gives for the unit vector e_J; checked at the first DoFs of each rank
   * that some point reaches (no constraints, so e_J is a field of the
   * space).
   */
  void
  check_spread_squares(Checker                         &check,
                       const Flow                      &flow,
                       const ImmersedCoupling          &coupling,
                       const std::vector<Tensor<1, 3>> &F)
  {
    std::vector<Tensor<1, 3>> w(F.size());
    for (unsigned int i = 0; i < F.size(); ++i)
      for (unsigned int c = 0; c < 3; ++c)
        w[i][c] = F[i][c] * F[i][c];
    AffineConstraints<double> none;
    none.close();
    VelocityVector squares = flow.vector();
    coupling.spread_squares(w, none, squares);
    std::vector<types::global_dof_index> mine;
    for (const auto J : squares.locally_owned_elements())
      if (squares(J) != 0. && mine.size() < 4)
        mine.push_back(J);
    double error = 0., largest = 0.;
    for (const auto &rank_dofs :
         Utilities::MPI::all_gather(MPI_COMM_WORLD, mine))
      for (const types::global_dof_index J : rank_dofs)
        {
          VelocityVector unit = flow.vector();
          if (unit.in_local_range(J))
            unit(J) = 1.;
          unit.update_ghost_values();
          const std::vector<Tensor<1, 3>> phi    = coupling.interpolate(unit);
          double                          probed = 0.;
          for (unsigned int i = 0; i < phi.size(); ++i)
            for (unsigned int c = 0; c < 3; ++c)
              probed += w[i][c] * phi[i][c] * phi[i][c];
          const double spread =
            Utilities::MPI::sum(squares.in_local_range(J) ? squares(J) : 0.,
                                MPI_COMM_WORLD);
          error   = std::max(error, std::abs(spread - probed));
          largest = std::max(largest, std::abs(probed));
        }
    std::cout << "  spread_squares: largest entry checked " << largest
              << ", largest error " << error << '\n';
    check.at_most("|spread_squares(w)_J - Σ_I w_I φ_J(x_I)²| / max",
                  error / largest,
                  1e-12);
  }

  void
  check_conservation_and_adjointness(Checker &check)
  {
    Flow             flow(1e-4);
    ImmersedCoupling coupling(flow.triangulation,
                              flow.fluid->get_mapping(),
                              flow.fluid->velocity_dof_handler());
    const Point<3>   center(10., 0.4, -0.3);
    const auto       x = membrane_nodes(center);
    coupling.place(x);
    const unsigned int own = coupling.n_locally_owned_points();
    std::cout << coupling.n_points() << " membrane points on "
              << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) << " rank(s), "
              << Utilities::MPI::min(own, MPI_COMM_WORLD) << " to "
              << Utilities::MPI::max(own, MPI_COMM_WORLD) << " per rank\n";
    check.near("each point on exactly one rank: Σ points per rank / points",
               Utilities::MPI::sum(own, MPI_COMM_WORLD) /
                 double(coupling.n_points()),
               1.,
               0.);

    std::mt19937                           random(11);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    std::vector<Tensor<1, 3>>              F(x.size());
    Tensor<1, 3>                           total_force, total_torque;
    double                                 largest = 0.;
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        for (unsigned int c = 0; c < 3; ++c)
          F[i][c] = uniform(random);
        total_force += F[i];
        total_torque += cross_product_3d(x[i] - center, F[i]);
        largest = std::max(largest, F[i].norm());
      }

    AffineConstraints<double> none;
    none.close();
    VelocityVector load = flow.vector();
    coupling.spread(F, none, load);
    for (unsigned int d = 0; d < 3; ++d)
      {
        Tensor<1, 3> e;
        e[d] = 1.;
        const auto translation =
          interpolated_field(flow, [&](const Point<3> &) { return e; });
        const auto rotation = interpolated_field(flow, [&](const Point<3> &p) {
          return cross_product_3d(e, p - center);
        });
        const std::string axis(1, "xyz"[d]);
        check.at_most("|⟨spread F, e_" + axis + "⟩ - Σ F_" + axis +
                        "| / max |F_I|",
                      std::abs((load * translation) - total_force[d]) / largest,
                      1e-11);
        check.at_most("|⟨spread F, e_" + axis +
                        " × (x - c)⟩ - (Σ (x_I - c) × F_I)_" + axis +
                        "| / max |F_I|",
                      std::abs((load * rotation) - total_torque[d]) / largest,
                      1e-10);
      }

    // A random v with the fluid's constraints (hanging nodes, zero on the
    // Dirichlet boundary), spread with the same constraints.
    VelocityVector v = flow.vector();
    for (const auto i : v.locally_owned_elements())
      v(i) = uniform(random);
    flow.fluid->velocity_zero_constraints().distribute(v);
    v.update_ghost_values();
    VelocityVector condensed = flow.vector();
    coupling.spread(F, flow.fluid->velocity_zero_constraints(), condensed);
    const auto v_at_points = coupling.interpolate(v);
    double     power = 0., scale = 0.;
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        power += F[i] * v_at_points[i];
        scale += F[i].norm() * v_at_points[i].norm();
      }
    std::cout << "  ⟨spread F, v⟩ = " << condensed * v
              << ", Σ F_I · v_I = " << power << '\n';
    check.at_most("|⟨spread F, v⟩ - Σ F_I · v_I| / Σ |F_I| |v_I| (adjointness)",
                  std::abs(condensed * v - power) / scale,
                  1e-12);
    check_spread_squares(check, flow, coupling, F);
  }

  /**
   * Steady Poiseuille flow (one Stokes step from rest is steady to round-off
   * at ρR²/μ = 2e-5 s ≪ Δt), then 40 explicit steps x ← x + Δt v(x) of the
   * membrane points: on the exact flow they travel along x at u(r), so
   * every point's path is compared with x_I + u(r_I) t e_x.
   */
  void
  check_tracers(Checker &check)
  {
    const double     dt = 1e-4;
    Flow             flow(dt);
    ImmersedCoupling coupling(flow.triangulation,
                              flow.fluid->get_mapping(),
                              flow.fluid->velocity_dof_handler());
    flow.fluid->advance();
    auto       x  = membrane_nodes(Point<3>(6., 0.5, 0.));
    const auto x0 = x;
    coupling.place(x);
    const unsigned int n_steps = 40;
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        const auto v = coupling.interpolate(flow.fluid->solution().block(0));
        for (unsigned int i = 0; i < x.size(); ++i)
          x[i] += dt * v[i];
        coupling.place(x);
      }
    const double R      = geometry.capillary_radius,
                 u_mean = FluidParameters().inlet_mean_speed;
    double worst = 0., travelled = 0.;
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        const double r2    = x0[i][1] * x0[i][1] + x0[i][2] * x0[i][2];
        Point<3>     exact = x0[i];
        exact[0] += 2. * u_mean * (1. - r2 / (R * R)) * n_steps * dt;
        worst     = std::max(worst, (x[i] - exact).norm());
        travelled = std::max(travelled, (exact - x0[i]).norm());
      }
    std::cout << "  tracers: largest path " << travelled
              << " µm, largest deviation from the exact path " << worst
              << " µm\n";
    // The level-1 velocity's own error (a few 1e-3 of ū near the wall) bounds
    // it.
    check.at_most("tracer membrane: max |x_I - x_I,exact| / largest path",
                  worst / travelled,
                  1e-2);
  }

  void
  check_lost_point(Checker &check)
  {
    Flow             flow(1e-4);
    ImmersedCoupling coupling(flow.triangulation,
                              flow.fluid->get_mapping(),
                              flow.fluid->velocity_dof_handler());
    auto             x = membrane_nodes(Point<3>(10., 0., 0.));
    coupling.place(x);
    coupling.place(x); // points on edges of curved cells must not get lost
    x[7] = Point<3>(10., 0., 5.2); // through the wall at r = 5 µm
    std::string message;
    try
      {
        coupling.place(x);
      }
    catch (const std::exception &e)
      {
        message = e.what();
      }
    std::cout << "  " << message << '\n';
    check.holds("a point pushed through the wall is reported by its index",
                message.find("membrane point 7 ") != std::string::npos);
  }

  /**
   * A membrane carried from x = 3 µm to x = 17 µm in steps of 0.25 µm on a
   * fully distributed capillary mesh: at every step each point must be on
   * exactly one rank, and spreading a unit axial force on every point must
   * give the total force; on several ranks points must change rank.
   */
  void
  check_partition_crossing(Checker &check)
  {
    parallel::fullydistributed::Triangulation<3> mesh(MPI_COMM_WORLD);
    create_distributed_mesh_hierarchy(
      mesh,
      [](Triangulation<3> &serial) { create_fluid_mesh(serial, geometry, 0); },
      [](Triangulation<3> &serial, const MeshZone &zone) {
        zone.refine_global(serial, 1);
      },
      false);
    const MappingQ<3> mapping(2);
    const FESystem<3> fe(FE_Q<3>(2), 3);
    DoFHandler<3>     dofs(mesh);
    dofs.distribute_dofs(fe);
    const IndexSet relevant = DoFTools::extract_locally_relevant_dofs(dofs);
    VelocityVector unit(dofs.locally_owned_dofs(), relevant, MPI_COMM_WORLD);
    VectorTools::interpolate(mapping,
                             dofs,
                             Functions::ConstantFunction<3>(
                               std::vector<double>{1., 0., 0.}),
                             unit);
    AffineConstraints<double> none;
    none.close();
    ImmersedCoupling coupling(mesh, mapping, dofs);

    const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    auto               x    = membrane_nodes(Point<3>(3., 0.3, 0.));
    const std::vector<Tensor<1, 3>> F(x.size(), Tensor<1, 3>({1., 0., 0.}));
    std::vector<unsigned int>       last_holder;
    unsigned int                    worst_miscount = 0, changes = 0;
    double                          worst_force = 0.;
    for (unsigned int step = 0; step <= 56; ++step)
      {
        coupling.place(x);
        // Each point counted by the ranks that hold it: once, if right.
        std::vector<unsigned int> holders(x.size(), 0), holder(x.size(), 0);
        for (const unsigned int i : coupling.locally_owned_point_indices())
          {
            holders[i] = 1;
            holder[i]  = rank;
          }
        Utilities::MPI::sum(holders, MPI_COMM_WORLD, holders);
        Utilities::MPI::sum(holder, MPI_COMM_WORLD, holder);
        for (unsigned int i = 0; i < x.size(); ++i)
          {
            worst_miscount =
              std::max(worst_miscount,
                       holders[i] > 1 ? holders[i] - 1 : 1 - holders[i]);
            if (!last_holder.empty())
              changes += holder[i] != last_holder[i];
          }
        last_holder = holder;

        VelocityVector load(dofs.locally_owned_dofs(),
                            relevant,
                            MPI_COMM_WORLD);
        coupling.spread(F, none, load);
        worst_force =
          std::max(worst_force,
                   std::abs(load * unit - double(x.size())) / double(x.size()));
        for (auto &p : x)
          p[0] += 0.25;
      }
    std::cout << "  " << x.size()
              << " points carried 14 µm in 56 steps: " << changes
              << " changes of rank\n";
    check.near("|ranks holding a point - 1|, worst point and step",
               worst_miscount,
               0.,
               0.);
    check.at_most("|⟨spread F, e_x⟩ - Σ F_x| / Σ F_x, worst step",
                  worst_force,
                  1e-12);
    if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
      check.at_least("points that changed rank, summed over the steps",
                     changes,
                     x.size());
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports
  Checker check;
  check_conservation_and_adjointness(check);
  check_tracers(check);
  check_lost_point(check);
  check_partition_crossing(check);
  return check.exit_code();
}

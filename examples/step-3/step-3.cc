/* ---------------------------------------------------------------------
 * rbc-ifem tutorial step-3: a red cell in the capillary.
 *
 * The immersed finite element method of the paper (An et al., Cells 2022,
 * Sec. 2.2) written out: a red cell carried by the plasma through the
 * capillary deforms, and every few steps the CO uptake of its current
 * shape is solved. The time loop below is the paper's six steps, in the
 * order IFEMSimulation (the class behind Experiment = flow) runs them; a
 * reader can change one of them here. examples/step-3/README.md is this
 * program's page.
 * --------------------------------------------------------------------- */

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/coupling/immersed_coupling.h>
#include <rbc_ifem/coupling/time_step_limit.h>
#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>

#include <iostream>

using namespace dealii;
using namespace rbc_ifem;

// DM of the cells' current shapes: the uptake solve of step-1 (mesh,
// refinement, CODiffusion) in one object, UptakeSolver, which takes the
// membranes as they are now, and the mapping that curves them through
// their nodes.
double
current_dm(const UptakeSolver &uptake, const CellPopulation &cells)
{
  return uptake.solve(cells.membrane_surfaces()).dm_total;
}

// Parse @p file into @p parameters, bound to @p prm, and check them.
void
read_parameters(const std::string &file,
                Parameters        &parameters,
                ParameterHandler  &prm)
{
  parameters.add_parameters(prm);
  prm.parse_input(file);
  parameters.validate();
}

// step-3.csv in @p directory, from rank 0.
void
write_table(const CsvTable           &table,
            const std::string        &directory,
            const MPI_Comm            communicator,
            const ConditionalOStream &pcout)
{
  create_output_directory(directory, communicator);
  if (Utilities::MPI::this_mpi_process(communicator) == 0)
    table.write(directory + "/step-3.csv");
  pcout << "wrote " << directory << "/step-3.csv" << std::endl;
}

// The fluid mesh of @p domain, refined around the cells' starting place,
// where the frame keeps them.
void
make_fluid_mesh(Triangulation<3>     &triangulation,
                const FlowDomain     &domain,
                const CellPopulation &cells,
                const Parameters     &parameters)
{
  domain.create_mesh(triangulation);
  triangulation.refine_global(domain.n_global_refinements);
  refine_near_points(triangulation,
                     cells.points(),
                     parameters.mesh.band_width,
                     parameters.mesh.fluid_band_refinements);
}

// The coupling is explicit: Δt must stay below about 0.7 of the estimate
// of the membrane's stiffest mode (doc/ifem.md), which this prints with
// the problem's sizes.
void
report_sizes(const CellPopulation     &cells,
             const ImmersedCoupling   &coupling,
             const FluidProblem       &fluid,
             const Parameters         &parameters,
             const ConditionalOStream &pcout)
{
  const double                dt = parameters.time.time_step;
  const CouplingTimeStepLimit limit(parameters.fluid.viscosity,
                                    parameters.membrane,
                                    cells.point_spacing(),
                                    coupling.mesh_size_at_points());
  pcout << cells.n_points() << " membrane points, " << fluid.n_dofs()
        << " fluid DoFs; Δt = " << dt << " s, " << dt / limit.limit
        << " of the explicit-coupling limit" << std::endl;
}

// A row of step-3.csv and the line that says it: DM at @p time and the
// shape of the cell then.
void
record_row(CsvTable                 &table,
           const double              time,
           const double              dm,
           const CellPopulation     &cells,
           const ConditionalOStream &pcout)
{
  const CellShape shape = cells.shapes()[0];
  const double    dv    = shape.volume / cells.reference_volume(0) - 1.;
  pcout << "t = " << time << " s: DM " << dm
        << " µm³/(s Torr), deformation index " << shape.deformation_index
        << ", volume change " << dv << std::endl;
  table.add(time, dm, shape.deformation_index, dv);
}

// @sect3{One time step: the paper's six steps}
//
// The cells' positions and the fluid's velocity at the step's start are
// given (1); the rest of the step, in the order IFEMSimulation::advance()
// runs it.
void
advance(CellPopulation   &cells,
        ImmersedCoupling &coupling,
        FluidProblem     &fluid,
        VelocityVector   &load,
        const double      dt)
{
  // 2. The forces on the membrane points: -∂E/∂x of the cells' energy
  // (elasticity, bending, area, volume, contact), exact.
  const std::vector<Tensor<1, 3>> forces = cells.compute_forces();

  // 3. Spread them to the fluid: f_J = Σ_I F_I φ_J(x_I).
  load = 0.;
  coupling.spread(forces, fluid.velocity_zero_constraints(), load);
  fluid.set_body_force(load);

  // 4. One Stokes step for v and p.
  fluid.advance();

  // 5. Interpolate the new velocity to the points: v_I = Σ_J v_J φ_J.
  const std::vector<Tensor<1, 3>> velocities =
    coupling.interpolate(fluid.solution().block(0));

  // 6. Move the points, x += Δt v_I, and find their cells anew.
  cells.move(velocities, dt);
  coupling.place(cells.points());

  // The frame follows the cell: its velocity grows by the cell's mean
  // axial velocity in it, so the cell stays in the short segment.
  double mean_velocity = 0.;
  for (const Tensor<1, 3> &v : velocities)
    mean_velocity += v[0] / velocities.size();
  fluid.set_frame_velocity(fluid.get_frame_velocity() + mean_velocity);
}

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   communicator = MPI_COMM_WORLD;
  ConditionalOStream               pcout(std::cout,
                           Utilities::MPI::this_mpi_process(communicator) == 0);
  TimerOutput                      timer(communicator,
                    pcout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  // The parameters, as in step-1.
  Parameters       parameters;
  ParameterHandler prm;
  read_parameters(argc > 1 ? argv[1] : "step-3.prm", parameters, prm);
  const double dt = parameters.time.time_step;

  // @sect3{The capillary, the plasma and the cell}
  //
  // FlowDomain::capillary() says where the cells flow: the lumen mesh
  // maker, the Poiseuille drive, where subsection Layout puts the cells,
  // the wall. The fluid mesh never moves; it is refined once around the
  // cell's starting place, where the frame keeps the cell.
  const FlowDomain domain = FlowDomain::capillary(parameters);
  CellPopulation   cells(domain.placements,
                       parameters.cells,
                       parameters.membrane);
  // The membranes' elasticity is always among the cell forces; add the
  // contact forces of subsection Cell interactions (here: the wall's).
  add_interaction_forces(cells,
                         parameters.interactions,
                         domain.wall_radius,
                         domain.period);

  parallel::shared::Triangulation<3> triangulation(
    communicator,
    Triangulation<3>::none,
    false,
    parallel::shared::Triangulation<3>::partition_metis);
  make_fluid_mesh(triangulation, domain, cells, parameters);

  // Q2-Q1 unsteady Stokes, backward Euler, matrix-free: setup() builds the
  // DoFs, the operators and the multigrid levels of the velocity once.
  FluidProblem fluid(triangulation, parameters.fluid, domain.drive, dt, timer);
  fluid.setup();

  // The membrane points located on the fluid mesh: spreading and
  // interpolation use the same shape functions φ_J(x_I), so they are
  // adjoint (the power the membrane gives the fluid is the power the
  // fluid takes).
  ImmersedCoupling coupling(triangulation,
                            fluid.get_mapping(),
                            fluid.velocity_dof_handler());
  coupling.place(cells.points());

  report_sizes(cells, coupling, fluid, parameters, pcout);

  VelocityVector load;
  fluid.initialize_velocity_vector(load);
  CsvTable table("time,dm_total,deformation_index,volume_change");
  // The uptake solve, built once; it makes a mesh around the membranes
  // each time it is asked.
  const UptakeSolver uptake(parameters.geometry,
                            parameters.mesh,
                            parameters.diffusion,
                            communicator,
                            timer);
  record_row(table, 0., current_dm(uptake, cells), cells, pcout);

  // @sect3{The time loop}
  for (unsigned int step = 1; step <= parameters.time.n_steps; ++step)
    {
      advance(cells, coupling, fluid, load, dt);
      // Every Diffusion interval steps: DM of the shape the cell has now.
      if (step % parameters.immersed.diffusion_interval == 0)
        record_row(table, step * dt, current_dm(uptake, cells), cells, pcout);
    }

  write_table(table, parameters.output_directory, communicator, pcout);
}

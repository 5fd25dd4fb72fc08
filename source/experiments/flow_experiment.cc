#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/experiments/flow_experiment.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>

#include <cmath>

namespace rbc_ifem
{
  FlowExperiment::FlowExperiment(const ExperimentContext &context)
    : Experiment(context, ParametersFile::before_work)
    , triangulation(communicator)
    , fluid(triangulation,
            parameters.fluid,
            FlowDrive::capillary(parameters.fluid, parameters.geometry),
            parameters.time.plasma_time_step(),
            timer)
  {}

  void
  FlowExperiment::setup()
  {
    const FluidParameters &f = parameters.fluid;
    pcout << "  " << name_of(f.model, fluid_model_names())
          << ", Reynolds number ρ ū 2R / μ = "
          << f.density * std::abs(f.inlet_mean_speed) * 2. *
               parameters.geometry.capillary_radius / f.viscosity
          << std::endl;
    std::vector<std::shared_ptr<const Triangulation<3>>> coarser_meshes;
    {
      TimerOutput::Scope scope(timer, "fluid mesh");
      const bool         periodic = parameters.geometry.periodic;
      coarser_meshes              = create_distributed_mesh_hierarchy(
        triangulation,
        [&](Triangulation<3> &serial) {
          create_fluid_mesh(serial, parameters.geometry, 0);
          if (periodic)
            add_end_periodicity(serial);
        },
        [&](Triangulation<3> &serial, const MeshZone &zone) {
          zone.refine_global(serial, parameters.mesh.fluid_global_refinements);
        },
        periodic);
    }
    fluid.setup(coarser_meshes);
    pcout << "  mesh: " << triangulation.n_global_active_cells() << " cells; "
          << fluid.n_dofs() << " DoFs ("
          << fluid.velocity_dof_handler().n_dofs() << " velocity, "
          << fluid.pressure_dof_handler().n_dofs() << " pressure); "
          << multigrid_levels_text(fluid) << std::endl;
  }

  void
  FlowExperiment::execute()
  {
    const std::string &directory = parameters.output_directory;
    CsvTable           table("time,flow_rate,pressure_drop,max_velocity,"
                             "divergence_l2,frame_velocity,newton_iterations,"
                             "linear_iterations,lab_flow_rate");
    std::vector<std::pair<double, std::string>> fields;
    const unsigned int n_steps = parameters.time.n_steps;
    const double       dt      = parameters.time.plasma_time_step();
    Timer              clock;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        const double time = step * dt;
        StepReport   report;
        try
          {
            report = fluid.advance();
          }
        catch (const SolverFailure &)
          {
            // The table up to the last good step, then stop.
            write_on_rank_0(communicator,
                            [&]() { table.write(directory + "/flow.csv"); });
            throw;
          }
        const FlowMeasures m = fluid.measure();
        table.add(time,
                  m.flow_rate,
                  m.pressure_drop,
                  m.max_velocity,
                  m.divergence_l2,
                  parameters.fluid.frame_velocity,
                  report.newton_iterations,
                  report.linear_iterations,
                  m.lab_flow_rate);
        pcout << "  step " << step << " of " << n_steps << ", t = " << time
              << " of " << n_steps * dt << " s: " << report.newton_iterations
              << " Newton, " << report.linear_iterations
              << " FGMRES iterations, residual " << report.residuals.front()
              << " -> " << report.final_residual << "; flow " << m.flow_rate
              << " µm³/s, Δp " << m.pressure_drop << " Pa, |∇·v| "
              << m.divergence_l2 << "  "
              << time_left_text(clock.wall_time(), step, n_steps - step)
              << std::endl;

        if (step % parameters.time.output_interval == 0 || step == n_steps)
          {
            write_together(communicator, [&]() {
              fields.emplace_back(time, fluid.write_vtu(directory, step));
              write_pvd(directory, "flow", fields, communicator);
              if (Utilities::MPI::this_mpi_process(communicator) == 0)
                table.write(directory + "/flow.csv");
            });
          }
      }
  }
} // namespace rbc_ifem

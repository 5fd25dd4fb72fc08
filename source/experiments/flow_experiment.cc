#include <rbc_ifem/base/output.h>
#include <rbc_ifem/experiments/flow_experiment.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <fstream>
#include <iomanip>

namespace rbc_ifem
{
  FlowExperiment::FlowExperiment(const Parameters &parameters,
                                 const MPI_Comm    communicator)
    : parameters(parameters)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(communicator,
                    Triangulation<3>::none,
                    false,
                    parallel::shared::Triangulation<3>::partition_metis)
    , fluid(triangulation,
            parameters.fluid,
            FlowDrive::capillary(parameters.fluid, parameters.geometry),
            parameters.time.time_step,
            timer)
  {}

  void
  FlowExperiment::run(const ParameterHandler &prm)
  {
    const FluidParameters &f = parameters.fluid;
    const double reynolds    = f.density * std::abs(f.inlet_mean_speed) * 2. *
                            parameters.geometry.capillary_radius / f.viscosity;
    pcout << "rbc-ifem: experiment 'flow' (" << f.model << ") on "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)\n"
          << "  Reynolds number ρ ū 2R / μ = " << reynolds << std::endl;

    {
      TimerOutput::Scope scope(timer, "fluid mesh");
      create_fluid_mesh(triangulation,
                        parameters.geometry,
                        parameters.mesh.fluid_global_refinements);
    }
    fluid.setup();
    pcout << "  mesh: " << triangulation.n_active_cells() << " cells; "
          << fluid.get_dof_handler().n_dofs() << " DoFs ("
          << fluid.owned_partitioning()[0].size() << " velocity, "
          << fluid.owned_partitioning()[1].size() << " pressure)" << std::endl;

    const std::string &directory = parameters.output_directory;
    create_output_directory(directory, communicator);
    const bool    root = Utilities::MPI::this_mpi_process(communicator) == 0;
    std::ofstream table;
    if (root)
      {
        write_file_atomically(directory + "/parameters.prm",
                              [&](std::ostream &out) {
                                prm.print_parameters(out,
                                                     ParameterHandler::PRM);
                              });
        table.open(directory + "/flow.csv");
        table << "time,flow_rate,pressure_drop,max_velocity,divergence_l2,"
                 "frame_velocity,newton_iterations,linear_iterations\n"
              << std::setprecision(10);
      }

    std::vector<std::pair<double, std::string>> fields;
    for (unsigned int step = 1; step <= parameters.time.n_steps; ++step)
      {
        const double       time   = step * parameters.time.time_step;
        const StepReport   report = fluid.advance();
        const FlowMeasures m      = fluid.measure();
        if (root)
          table << time << ',' << m.flow_rate << ',' << m.pressure_drop << ','
                << m.max_velocity << ',' << m.divergence_l2 << ','
                << f.frame_velocity << ',' << report.newton_iterations << ','
                << report.linear_iterations << std::endl;
        pcout << "  step " << step << ", t = " << time
              << " s: " << report.newton_iterations << " Newton, "
              << report.linear_iterations << " FGMRES iterations, residual "
              << report.residuals.front() << " -> " << report.final_residual
              << "; flow " << m.flow_rate << " µm³/s, Δp " << m.pressure_drop
              << " pN/µm², |∇·v| " << m.divergence_l2 << std::endl;

        if (step % parameters.time.output_interval == 0 ||
            step == parameters.time.n_steps)
          {
            fields.emplace_back(time, fluid.write_vtu(directory, step));
            write_pvd(directory, "flow", fields, communicator);
          }
      }
    write_timing(timer, directory, communicator);
    pcout << "  wrote " << directory
          << "/: parameters.prm, flow.csv, flow.pvd, timing.csv" << std::endl;
    pcout << "  peak memory: " << peak_memory_mb(communicator)
          << " MB (largest over ranks)" << std::endl;
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/experiments/diffusion_experiment.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/ifem/ifem_simulation.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// One CSV row from numbers, at full precision.
    template <typename... Values>
    std::string
    csv_row(const Values &...values)
    {
      std::ostringstream row;
      row << std::setprecision(10);
      const char *separator = "";
      ((row << separator << values, separator = ","), ...);
      return row.str();
    }

    /// Everything in a checkpoint: the run's record, the fluid, the membranes.
    struct Checkpoint
    {
      unsigned int                n_ranks = 0;
      RunRecord                   record;
      FluidState                  fluid;
      std::vector<Vector<double>> positions;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int)
      {
        archive &n_ranks &record &fluid &positions;
      }
    };
  } // namespace

  CouplingTimeStepLimit::CouplingTimeStepLimit(const double viscosity,
                                               const MembraneParameters &m,
                                               const double point_spacing,
                                               const double mesh_size)
  {
    const double q = numbers::PI / std::max(point_spacing, 0.5 * mesh_size);
    in_plane =
      8. * viscosity / ((m.area_dilation_modulus + m.shear_modulus) * q);
    bending = 8. * viscosity / (m.bending_modulus * q * q * q);
    limit   = std::min(in_plane, bending);
  }


  IFEMSimulation::IFEMSimulation(const Parameters &parameters,
                                 const MPI_Comm    communicator,
                                 const FlowDomain &domain)
    : parameters(parameters)
    , communicator(communicator)
    , domain(domain)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    // Rank 0's own clock: a TimerOutput on the world communicator warns at
    // length when an exception unwinds through it.
    , timer(MPI_COMM_SELF, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(communicator,
                    Triangulation<3>::none,
                    false,
                    parallel::shared::Triangulation<3>::partition_metis)
    , fluid(triangulation,
            parameters.fluid,
            domain.drive,
            parameters.time.time_step,
            timer)
    , cells(domain.placements, parameters.cells, parameters.membrane)
  {
    record.cell_files.resize(cells.size());
    cells.hold(parameters.immersed.tether_stiffness);
  }

  void
  IFEMSimulation::setup()
  {
    {
      TimerOutput::Scope scope(timer, "fluid mesh");
      domain.create_mesh(triangulation, parameters);
      refine_near_points(triangulation,
                         cells.points(),
                         parameters.mesh.band_width,
                         parameters.mesh.fluid_band_refinements);
    }
    fluid.setup();
    coupling = std::make_unique<ImmersedCoupling>(triangulation,
                                                  fluid.get_mapping(),
                                                  fluid.get_dof_handler());
    try
      {
        coupling->place(cells.points());
      }
    catch (const std::runtime_error &e)
      {
        throw InputError("the cells do not fit into " + domain.name() + ": " +
                         e.what());
      }
    mesh_size = coupling->mesh_size_at_points();
    load.reinit(fluid.owned_partitioning(), communicator);
  }

  void
  IFEMSimulation::report_startup() const
  {
    const FluidParameters    &f      = parameters.fluid;
    const MembraneParameters &m      = parameters.membrane;
    const double              speed  = domain.velocity_scale(parameters);
    const double              length = domain.length_scale(parameters);
    const bool                box = domain.kind == FlowDomain::Kind::shear_box;
    const double              spacing = cells.point_spacing();
    const CouplingTimeStepLimit stable(f.viscosity, m, spacing, mesh_size);
    const double                stable_step = stable.limit;

    pcout << "  cells: " << cells.size() << ", " << cells.n_points()
          << " membrane points, spacing up to " << spacing
          << " µm; fluid mesh size at the cells h = " << mesh_size << " µm\n"
          << "  Reynolds number " << (box ? "ρ γ̇ a² / μ = " : "ρ ū 2R / μ = ")
          << f.density * speed * length / f.viscosity << "\n"
          << "  capillary number " << (box ? "μ a γ̇ / G = " : "μ ū / G = ")
          << f.viscosity * speed / m.shear_modulus << "\n"
          << "  explicit-coupling time step limit ≈ " << stable_step
          << " s (in-plane " << stable.in_plane << " s, bending "
          << stable.bending
          << " s); runs stay stable below about 0.7 of it (doc/ifem.md); Δt = "
          << parameters.time.time_step << " s" << std::endl;
    if (parameters.time.time_step > stable_step)
      pcout << "  WARNING: Time/Time step = " << parameters.time.time_step
            << " s exceeds the explicit-coupling estimate " << stable_step
            << " s; the run may become unstable." << std::endl;
    if (spacing > 0.5 * mesh_size)
      pcout
        << "  WARNING: the membrane point spacing " << spacing
        << " µm exceeds half the fluid mesh size at the cells, h/2 = "
        << 0.5 * mesh_size
        << " µm (the paper's rule): raise Cells/Surface refinements or lower "
           "Mesh/Fluid band refinements."
        << std::endl;
  }

  StepReport
  IFEMSimulation::advance()
  {
    const double                      dt        = parameters.time.time_step;
    const std::vector<Vector<double>> last_good = cells.positions();

    std::vector<Tensor<1, 3>> forces;
    {
      TimerOutput::Scope scope(timer, "membrane forces");
      forces = cells.compute_forces();
    }
    for (const Tensor<1, 3> &force : forces)
      if (!std::isfinite(force.norm()))
        stop("the membrane forces are not finite", last_good);
    {
      TimerOutput::Scope scope(timer, "coupling: spread");
      load = 0.;
      coupling->spread(forces, fluid.zero_constraints(), load);
      fluid.set_body_force(load);
    }

    StepReport report;
    try
      {
        report = fluid.advance();
      }
    catch (const SolverFailure &e)
      {
        stop(e.what(), last_good);
      }

    std::vector<Tensor<1, 3>> velocities;
    {
      TimerOutput::Scope scope(timer, "coupling: interpolate");
      velocities = coupling->interpolate(fluid.solution());
    }
    double largest_move = 0., mean_axial_velocity = 0.;
    for (const Tensor<1, 3> &v : velocities)
      {
        largest_move = std::max(largest_move, v.norm() * dt);
        mean_axial_velocity += v[0] / velocities.size();
      }
    if (!(largest_move <=
          parameters.immersed.max_step_displacement * mesh_size))
      {
        std::ostringstream why;
        why
          << "a membrane point moved " << largest_move
          << " µm in one step, more than "
          << "Immersed cells/Maximum step displacement = "
          << parameters.immersed.max_step_displacement
          << " of the fluid mesh size " << mesh_size
          << " µm: the explicit coupling is unstable; reduce Time/Time step = "
          << dt << " s";
        stop(why.str(), last_good);
      }

    {
      TimerOutput::Scope scope(timer, "coupling: move and place");
      cells.move(velocities, dt);
      try
        {
          coupling->place(cells.points());
        }
      catch (const std::runtime_error &e)
        {
          stop(e.what(), last_good);
        }
    }

    record.frame_offset += fluid.get_frame_velocity() * dt;
    record.time += dt;
    ++record.step;
    if (parameters.immersed.follow_cells)
      fluid.set_frame_velocity(fluid.get_frame_velocity() +
                               mean_axial_velocity);
    return report;
  }

  double
  IFEMSimulation::solve_uptake(const unsigned int counter)
  {
    const auto surfaces = cells.current_surfaces();
    std::vector<const Triangulation<2, 3> *> pointers;
    for (const auto &surface : surfaces)
      pointers.push_back(surface.get());
    const std::string &directory = parameters.output_directory;
    const LayoutUptake uptake    = rbc_ifem::solve_uptake(
      parameters,
      pointers,
      cells.surface_mapping(),
      parameters.mesh.diffusion_band_refinements,
      communicator,
      timer,
      [&](const CODiffusion &diffusion) {
        const CODiffusion::OutputFiles files =
          diffusion.write_output(directory, "diffusion", counter);
        record.diffusion_files.emplace_back(record.time, files.pressure);
        record.flux_files.emplace_back(record.time, files.membranes);
        write_pvd(directory, "diffusion", record.diffusion_files, communicator);
        write_pvd(directory,
                  "diffusion_membranes",
                  record.flux_files,
                  communicator);
      });
    std::ostringstream row;
    row << csv_row(record.time, uptake.dm_total);
    for (const double dm : uptake.dm_cells)
      row << ',' << std::setprecision(10) << dm;
    record.dm_rows.push_back(row.str());
    return uptake.dm_total;
  }

  void
  IFEMSimulation::record_flow(const StepReport &report)
  {
    const FlowMeasures m    = fluid.measure();
    const Tensor<1, 3> held = cells.held_force();
    record.flow_rows.push_back(csv_row(record.time,
                                       m.flow_rate,
                                       m.pressure_drop,
                                       m.max_velocity,
                                       m.divergence_l2,
                                       fluid.get_frame_velocity(),
                                       report.newton_iterations,
                                       report.linear_iterations,
                                       held[0],
                                       held[1],
                                       held[2]));
  }

  std::vector<CellShape>
  IFEMSimulation::record_shapes()
  {
    const std::vector<CellShape> shapes = cells.shapes();
    for (unsigned int c = 0; c < shapes.size(); ++c)
      {
        const CellShape &s = shapes[c];
        record.cell_rows.push_back(
          csv_row(record.time,
                  c,
                  s.centroid[0] + record.frame_offset,
                  s.centroid[1],
                  s.centroid[2],
                  s.area,
                  s.volume,
                  s.axial_length,
                  s.max_radius,
                  s.deformation_index,
                  s.centroid[0],
                  s.volume / cells.reference_volume(c) - 1.,
                  s.area / cells.reference_area(c) - 1.,
                  s.taylor_deformation,
                  s.inclination));
      }
    if (domain.kind == FlowDomain::Kind::shear_box)
      record.shear_history.push_back(
        {{record.time, shapes[0].taylor_deformation, shapes[0].inclination}});
    return shapes;
  }

  void
  IFEMSimulation::write_fields()
  {
    TimerOutput::Scope scope(timer, "output");
    const std::string &directory = parameters.output_directory;
    record.fluid_files.emplace_back(record.time,
                                    fluid.write_vtu(directory, record.step));
    write_pvd(directory, "flow", record.fluid_files, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        const std::vector<std::string> files =
          cells.write_vtu(directory, "cell", record.step);
        for (unsigned int c = 0; c < cells.size(); ++c)
          {
            record.cell_files[c].emplace_back(record.time, files[c]);
            write_pvd(directory,
                      "cell_" + std::to_string(c),
                      record.cell_files[c],
                      communicator);
          }
      }
  }

  void
  IFEMSimulation::write_tables() const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const std::string &directory = parameters.output_directory;
    const auto         write     = [&](const std::string              &name,
                           const std::string              &header,
                           const std::vector<std::string> &rows) {
      write_file_atomically(directory + "/" + name, [&](std::ostream &out) {
        out << header << '\n';
        for (const std::string &row : rows)
          out << row << '\n';
      });
    };
    write(
      "flow.csv",
      "time,flow_rate,pressure_drop,max_velocity,divergence_l2,frame_velocity,"
      "newton_iterations,linear_iterations,held_force_x,held_force_y,held_force_z",
      record.flow_rows);
    write(
      "cells.csv",
      "time,cell,x,y,z,area,volume,axial_length,max_radius,deformation_index,frame_x,"
      "volume_change,area_change,taylor_deformation,inclination",
      record.cell_rows);
    if (domain.kind == FlowDomain::Kind::shear_box)
      {
        std::vector<std::string> rows;
        for (const auto &[time, deformation, inclination] :
             record.shear_history)
          rows.push_back(csv_row(time, deformation, inclination / numbers::PI));
        write("shear.csv", "time,taylor_deformation,inclination_over_pi", rows);
      }
    if (parameters.immersed.diffusion_interval > 0)
      {
        std::string header = "time,dm_total";
        for (unsigned int c = 0; c < cells.size(); ++c)
          header += ",dm_cell_" + std::to_string(c);
        write("dm.csv", header, record.dm_rows);
      }
  }

  void
  IFEMSimulation::write_checkpoint() const
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    Checkpoint         checkpoint;
    checkpoint.n_ranks   = Utilities::MPI::n_mpi_processes(communicator);
    checkpoint.record    = record;
    checkpoint.fluid     = fluid.state();
    checkpoint.positions = cells.positions();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output_directory + "/checkpoint.bin",
                            [&](std::ostream &out) {
                              boost::archive::binary_oarchive archive(out);
                              archive << checkpoint;
                            });
  }

  void
  IFEMSimulation::read_checkpoint()
  {
    const std::string path = parameters.output_directory + "/checkpoint.bin";
    std::ifstream     in(path, std::ios::binary);
    if (!in)
      throw InputError(
        "Immersed cells/Resume",
        "true",
        "it needs the checkpoint " + path +
          " of an earlier run, which does not exist or cannot be read.");
    Checkpoint checkpoint;
    try
      {
        boost::archive::binary_iarchive archive(in);
        archive >> checkpoint;
      }
    catch (const std::exception &e)
      {
        throw InputError("Immersed cells/Resume",
                         "true",
                         path + " is not a readable checkpoint.");
      }
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    if (checkpoint.n_ranks != n_ranks ||
        checkpoint.fluid.solution.size() != fluid.get_dof_handler().n_dofs() ||
        checkpoint.positions.size() != cells.size() ||
        checkpoint.positions[0].size() != cells.positions()[0].size())
      throw InputError(
        "Immersed cells/Resume",
        "true",
        "the checkpoint " + path + " comes from a run on " +
          std::to_string(checkpoint.n_ranks) + " rank(s) with " +
          std::to_string(checkpoint.fluid.solution.size()) +
          " fluid DoFs; this run has " + std::to_string(n_ranks) +
          " rank(s) and " + std::to_string(fluid.get_dof_handler().n_dofs()) +
          ": resume with the same parameter file and number of ranks.");
    if (checkpoint.record.step >= parameters.time.n_steps)
      throw InputError("Time/Number of steps",
                       std::to_string(parameters.time.n_steps),
                       "a resumed run must go beyond the checkpoint's step " +
                         std::to_string(checkpoint.record.step) + ".");
    record = checkpoint.record;
    fluid.set_state(checkpoint.fluid);
    cells.set_positions(checkpoint.positions);
    coupling->place(cells.points());
  }

  void
  IFEMSimulation::stop(const std::string                 &why,
                       const std::vector<Vector<double>> &last_good)
  {
    cells.set_positions(last_good);
    write_tables();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      cells.write_vtu(parameters.output_directory,
                      "last_good_cell",
                      record.step);
    throw SolverFailure(
      "step " + std::to_string(record.step + 1) +
      ", t = " + std::to_string(record.time) + " s: " + why +
      ". The tables so far and the last good membranes (last_good_cell_*.vtu) "
      "are in " +
      parameters.output_directory + ".");
  }

  const RunRecord &
  IFEMSimulation::run_record() const
  {
    return record;
  }

  void
  IFEMSimulation::run(const ParameterHandler &prm)
  {
    const ImmersedParameters &immersed = parameters.immersed;
    const TimeParameters     &time     = parameters.time;
    const bool                box = domain.kind == FlowDomain::Kind::shear_box;
    pcout << "rbc-ifem: "
          << (box ? "a capsule in the shear box" :
                    "experiment 'flow' with immersed cells")
          << " (" << parameters.fluid.model << ") on "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)"
          << std::endl;
    setup();
    pcout << "  fluid mesh: " << triangulation.n_active_cells() << " cells, "
          << fluid.get_dof_handler().n_dofs() << " DoFs" << std::endl;
    report_startup();
    if (immersed.resume)
      {
        read_checkpoint();
        pcout << "  resumed from the checkpoint at step " << record.step
              << ", t = " << record.time << " s" << std::endl;
      }

    const std::string &directory = parameters.output_directory;
    create_output_directory(directory, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(directory + "/parameters.prm",
                            [&](std::ostream &out) {
                              prm.print_parameters(out, ParameterHandler::PRM);
                            });

    const auto due = [](const unsigned int step, const unsigned int interval) {
      return interval > 0 && step % interval == 0;
    };
    if (record.step == 0)
      {
        record_shapes();
        if (immersed.diffusion_interval > 0)
          pcout << "  t = 0 s: DM " << solve_uptake(0) << " µm³/(s Torr)"
                << std::endl;
        write_fields();
        write_tables();
      }

    Timer              clock;
    const unsigned int first_step = record.step;
    while (record.step < time.n_steps)
      {
        const StepReport   report    = advance();
        const unsigned int step      = record.step;
        const bool         last      = step == time.n_steps;
        const bool         diffusion = due(step, immersed.diffusion_interval);
        const bool         output    = due(step, time.output_interval) || last;
        if (!(diffusion || output || due(step, immersed.progress_interval) ||
              due(step, immersed.checkpoint_interval)))
          continue;

        record_flow(report);
        std::ostringstream progress;
        progress << "  step " << step << ", t = " << record.time
                 << " s: " << report.linear_iterations
                 << " FGMRES iterations, frame velocity "
                 << fluid.get_frame_velocity() << " µm/s";
        if (diffusion)
          progress << ", DM "
                   << solve_uptake(step / immersed.diffusion_interval)
                   << " µm³/(s Torr)";
        const CellShape shape = (output ? record_shapes() : cells.shapes())[0];
        progress << "; cell 0: volume change "
                 << shape.volume / cells.reference_volume(0) - 1.
                 << ", deformation index " << shape.deformation_index;
        if (box)
          progress << ", Taylor deformation " << shape.taylor_deformation;
        if (output)
          {
            write_fields();
            write_tables();
          }
        pcout << progress.str() << std::endl;
        if (due(step, immersed.checkpoint_interval) ||
            (last && immersed.checkpoint_interval > 0))
          write_checkpoint();
      }
    write_tables();
    write_timing(timer, directory, communicator);
    const unsigned int n_run = record.step - first_step;
    pcout << "  " << n_run << " steps in " << clock.wall_time() << " s, "
          << clock.wall_time() / std::max(1u, n_run) << " s per step"
          << std::endl;
    timer.print_summary();
    pcout << "  wrote " << directory
          << "/: parameters.prm, flow.csv, cells.csv, "
          << (box ? "shear.csv, " : "")
          << (immersed.diffusion_interval > 0 ?
                "dm.csv, diffusion.pvd, diffusion_membranes.pvd, " :
                "")
          << (immersed.checkpoint_interval > 0 ? "checkpoint.bin, " : "")
          << "flow.pvd, cell_*.pvd, timing.csv" << std::endl;
    pcout << "  peak memory: " << peak_memory_mb(communicator)
          << " MB (largest over ranks)" << std::endl;
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/interruption.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/coupling/membrane_forces.h>
#include <rbc_ifem/coupling/point_exchange.h>
#include <rbc_ifem/coupling/pushing_force.h>
#include <rbc_ifem/coupling/semi_implicit_load.h>
#include <rbc_ifem/coupling/time_step_limit.h>
#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>
#include <rbc_ifem/ifem/ifem_simulation.h>
#include <rbc_ifem/ifem/membrane_series.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// The size estimate of a run, printed and checked (refused above the
    /// machine's memory unless @p options say --force).
    SizeEstimate
    checked_size(const Parameters   &parameters,
                 const FlowDomain   &domain,
                 const MPI_Comm      communicator,
                 const RunOptions   &options,
                 ConditionalOStream &pcout)
    {
      const SizeEstimate size(parameters,
                              domain,
                              Utilities::MPI::n_mpi_processes(communicator));
      pcout << "  " << size.text() << std::endl;
      size.check(communicator, options.force);
      return size;
    }
  } // namespace

  IFEMSimulation::IFEMSimulation(const Parameters  &parameters,
                                 const std::string &parameter_file_text,
                                 const FlowDomain  &domain,
                                 const MPI_Comm     communicator,
                                 TimerOutput       &timer,
                                 const RunOptions  &options)
    : parameters(parameters)
    , parameter_file_text(parameter_file_text)
    , communicator(communicator)
    , domain(domain)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(timer)
    , size_estimate(
        checked_size(parameters, domain, communicator, options, pcout))
    , triangulation(communicator)
    , fluid(triangulation,
            parameters.fluid,
            domain.drive,
            parameters.time.plasma_time_step(),
            timer)
    , cells(domain.placements,
            parameters.cells,
            parameters.membrane,
            communicator,
            domain.period)
    , uptake(parameters.geometry,
             parameters.mesh,
             parameters.diffusion,
             communicator,
             timer)
    , record(cells.size(), parameters.diffusion.uptake == CellUptake::reaction)
    , run_report(this->parameters, this->domain, communicator)
    , checkpoint(parameters.output_directory)
    , schedule(parameters.time, parameters.immersed)
    , volume_watch(cells.size(), parameters.immersed.max_volume_change)
  {
    add_cell_forces();
    contacts = cells.size() > 1 || domain.wall_radius.has_value();
  }

  void
  IFEMSimulation::add_cell_forces()
  {
    const ImmersedParameters &immersed = parameters.immersed;
    if (immersed.tether_stiffness > 0.)
      cells.add_force(std::make_unique<Tether>(cells.membranes(),
                                               immersed.tether_stiffness,
                                               cells.owners()));
    const std::vector<Tensor<1, 3>> pushes = immersed.pushing_force_vectors();
    if (!pushes.empty())
      {
        if (pushes.size() != cells.size())
          throw InputError("Immersed cells/Pushing forces",
                           immersed.pushing_forces,
                           "one force 'Fx, Fy, Fz' per cell: " +
                             std::to_string(cells.size()) +
                             " separated by ';', or none.");
        cells.add_force(std::make_unique<PushingForce>(cells.membranes(),
                                                       pushes,
                                                       cells.owners()));
      }
    add_interaction_forces(cells,
                           parameters.interactions,
                           domain.wall_radius,
                           domain.period);
    if (immersed.squeeze_into_lumen)
      {
        if (!domain.wall_radius || parameters.interactions.wall_pressure <= 0.)
          throw InputError("Immersed cells/Squeeze into lumen",
                           "true",
                           "cells squeezed into the capillary need its wall "
                           "repulsion: Cell interactions/Wall pressure > 0.");
      }
  }

  void
  IFEMSimulation::add_observer(RunObserver &observer)
  {
    observers.push_back(&observer);
  }

  void
  IFEMSimulation::setup()
  {
    // The squeeze shares the cells out as their forces are (by owner, or
    // within each membrane when there are fewer cells than ranks) and
    // squeezes each alone, along the same L-BFGS path on any number of
    // ranks (to round-off, with the membranes shared).
    if (parameters.immersed.squeeze_into_lumen)
      {
        TimerOutput::Scope  scope(timer, "squeeze into lumen");
        const WallRepulsion wall(
          cells.membranes(),
          *domain.wall_radius,
          RepulsivePotential(parameters.interactions.wall_pressure,
                             parameters.interactions.wall_range),
          cells.owners());
        std::vector<Vector<double>> x      = cells.positions();
        const unsigned int          stages = wall.squeeze_into_lumen(x);
        cells.set_positions(x);
        pcout << "  squeezed into the lumen in " << stages << " stages"
              << std::endl;
      }
    std::vector<std::shared_ptr<const Triangulation<3>>> coarser_meshes;
    {
      TimerOutput::Scope          scope(timer, "fluid mesh");
      const std::vector<Point<3>> band =
        points_in_segment(cells.points(), domain.period);
      const auto coarse = [&](Triangulation<3> &serial) {
        domain.create_mesh(serial);
        if (domain.period)
          add_end_periodicity(serial);
      };
      const auto refine = [&](Triangulation<3> &serial, const MeshZone &zone) {
        zone.refine_global(serial, domain.n_global_refinements);
        refine_near_points(serial,
                           band,
                           parameters.mesh.band_width,
                           parameters.mesh.fluid_band_refinements,
                           zone);
      };
      // Slabs of equal fine cells, not equal coarse cells: the band makes
      // the mesh finer where the cells are, all in one part of the
      // capillary in a clustered layout.
      const bool periodic = domain.period.has_value();
      coarser_meshes      = create_distributed_mesh_hierarchy(
        triangulation,
        coarse,
        refine,
        periodic,
        fine_cells_per_coarse_cell(communicator, coarse, refine, periodic));
    }
    fluid.setup(coarser_meshes);
    coupling = std::make_unique<ImmersedCoupling>(triangulation,
                                                  fluid.get_mapping(),
                                                  fluid.velocity_dof_handler(),
                                                  domain.period);
    try
      {
        coupling->place(cells.points());
      }
    catch (const std::runtime_error &e)
      {
        throw InputError("the cells do not fit into " + domain.name + ": " +
                         e.what());
      }
    mesh_size = coupling->mesh_size_at_points();
    fluid.initialize_velocity_vector(load);
    const CouplingTimeStepLimit stable = time_step_limit();
    time_step =
      parameters.time.coupled_time_step(stable, parameters.immersed.coupling);
    fluid.set_time_step(time_step);
    if (parameters.immersed.coupling == CouplingScheme::semi_implicit)
      setup_semi_implicit_load();

    pcout << "  fluid mesh: " << triangulation.n_global_active_cells()
          << " cells, " << fluid.n_dofs() << " DoFs; "
          << multigrid_levels_text(fluid) << std::endl;
    run_report.startup(cells, stable, mesh_size, time_step);
    report_load_balance();
    if (parameters.immersed.diffusion_interval > 0)
      check_uptake_input();
    if (parameters.immersed.resume)
      {
        read_checkpoint();
        pcout << "  resumed from " << checkpoint.resumed_from() << " at step "
              << record.step << ", t = " << record.time << " s" << std::endl;
      }
  }

  CouplingTimeStepLimit
  IFEMSimulation::time_step_limit() const
  {
    CouplingTimeStepLimit stable(parameters.fluid.viscosity,
                                 parameters.membrane,
                                 cells.point_spacing(),
                                 mesh_size);
    // Points at the run's speed move at most half of what a step allows.
    stable.include_advection(domain.velocity_scale,
                             0.5 * parameters.immersed.max_step_displacement *
                               mesh_size);
    if (!contacts)
      return stable;
    const auto [cell_gap, wall_gap]             = smallest_gaps();
    const InteractionParameters &contact        = parameters.interactions;
    const double                 membrane_limit = stable.limit;
    const auto                   stiffness =
      [](const double p0, const double range, const double gap) {
        return p0 > 0. && gap > 0. && gap < range ?
                 std::abs(RepulsivePotential(p0, range).pressure(gap).second) :
                 0.;
      };
    const double viscosity = parameters.fluid.viscosity;
    const double diameter  = parameters.cells.diameter;
    stable.include_contact(viscosity,
                           stiffness(contact.repulsion_pressure,
                                     contact.repulsion_range,
                                     cell_gap),
                           diameter);
    if (stable.contact < 0.01 * membrane_limit)
      throw InputError(
        "Layout/Minimum gap",
        to_text(parameters.layout.minimum_gap),
        "two cells start " + to_text(cell_gap) +
          " µm apart, where the repulsion (Cell interactions/Repulsion "
          "pressure and range) is so stiff that the step would have to be " +
          to_text(stable.contact) +
          " s, below a hundredth of the "
          "membranes' " +
          to_text(membrane_limit) + " s. Start the cells farther apart.");
    stable.include_contact(viscosity,
                           stiffness(contact.wall_pressure,
                                     contact.wall_range,
                                     wall_gap),
                           diameter);
    return stable;
  }

  void
  IFEMSimulation::setup_semi_implicit_load()
  {
    semi_implicit = std::make_unique<SemiImplicitLoad>(
      *coupling, cells, fluid.velocity_zero_constraints(), time_step);
    multilevel_term =
      std::make_unique<MultilevelMembraneTerm>(fluid.velocity_levels(),
                                               fluid.get_level_mapping(),
                                               *semi_implicit,
                                               cells,
                                               domain.period,
                                               time_step);
    fluid.set_velocity_load([this](const auto &v, auto &result) {
      TimerOutput::Scope scope(timer, "coupling: implicit force load");
      (*semi_implicit)(v, result);
    });
  }

  StepReport
  IFEMSimulation::advance()
  {
    const double                      dt        = time_step;
    const std::vector<Vector<double>> last_good = cells.positions();

    std::vector<Tensor<1, 3>> forces;
    {
      TimerOutput::Scope scope(timer, "membrane forces");
      forces = cells.compute_owned_forces();
    }
    if (parameters.immersed.coupling == CouplingScheme::semi_implicit)
      {
        {
          TimerOutput::Scope scope(timer, "membrane stiffness");
          cells.linearize();
        }
        TimerOutput::Scope scope(timer, "coupling: multigrid levels");
        multilevel_term->update();
      }
    if (!cells.forces_finite())
      stop("the membrane forces are not finite", last_good);
    {
      TimerOutput::Scope scope(timer, "coupling: spread");
      // From each cell's owner to the ranks whose fluid cells hold its
      // points, not summed over all ranks.
      const std::vector<unsigned int> &fluid_ranks = coupling->point_ranks();
      PointExchange(communicator, fluid_ranks, cells.point_owners(fluid_ranks))
        .to_fluid_ranks(forces);
      load = 0.;
      coupling->spread(forces, fluid.velocity_zero_constraints(), load);
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
      velocities = coupling->interpolate(fluid.solution().block(0));
    }
    check_displacement(velocities, last_good);
    cells.move(velocities, dt);
    watch_volumes(last_good);
    if (contacts)
      check_gaps(last_good);
    {
      TimerOutput::Scope scope(timer, "coupling: move and place");
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
      {
        double mean_axial_velocity = 0.;
        for (const Tensor<1, 3> &v : velocities)
          mean_axial_velocity += v[0] / velocities.size();
        fluid.set_frame_velocity(fluid.get_frame_velocity() +
                                 mean_axial_velocity);
      }
    return report;
  }

  void
  IFEMSimulation::watch_volumes(const std::vector<Vector<double>> &last_good)
  {
    const std::vector<double> volumes = cells.volumes();
    std::vector<double>       changes;
    for (unsigned int c = 0; c < cells.size(); ++c)
      changes.push_back(volumes[c] / cells.reference_volume(c) - 1.);
    const std::string why = volume_watch.add(changes);
    if (!why.empty())
      stop(why, last_good);
  }

  void
  IFEMSimulation::check_displacement(
    const std::vector<Tensor<1, 3>>   &velocities,
    const std::vector<Vector<double>> &last_good)
  {
    double largest_move = 0.;
    for (const Tensor<1, 3> &v : velocities)
      largest_move = std::max(largest_move, v.norm() * time_step);
    if (largest_move <= parameters.immersed.max_step_displacement * mesh_size)
      return;
    std::ostringstream why;
    why << "a membrane point moved " << largest_move
        << " µm in one step, more than "
        << "Immersed cells/Maximum step displacement = "
        << parameters.immersed.max_step_displacement
        << " of the fluid mesh size " << mesh_size << " µm: the "
        << name_of(parameters.immersed.coupling, coupling_scheme_names())
        << " coupling is unstable or the step too long; reduce Time/Time "
           "step = "
        << time_step << " s";
    stop(why.str(), last_good);
  }

  void
  IFEMSimulation::check_uptake_input() const
  {
    TimerOutput::Scope scope(timer, "diffusion: input check");
    uptake.check(cells.membrane_surfaces());
  }

  double
  IFEMSimulation::solve_uptake(const unsigned int counter)
  {
    const std::string &directory = parameters.output_directory;
    Uptake             now;
    try
      {
        now = uptake.solve(cells.membrane_surfaces(),
                           [&](const DiffusionSolver &diffusion) {
                             record.uptake_fields.write(diffusion,
                                                        directory,
                                                        record.time,
                                                        counter,
                                                        communicator,
                                                        frame_data());
                           });
      }
    catch (const OutputError &)
      {
        throw;
      }
    catch (const std::runtime_error &e)
      {
        // At the start the cells are the input, and what the solve
        // refuses (InputError) is bad input; later they are where the flow
        // took them, and the run stops with its state.
        if (record.step == 0)
          throw;
        stop("the CO uptake solve on the cells' current shapes failed: " +
               std::string(e.what()),
             cells.positions(),
             true);
      }
    record.dm.add_row(dm_row(record.time, now));
    record.dm_history.emplace_back(record.time, now.dm_total);
    if (!observers.empty())
      {
        const double gap = smallest_cell_gap();
        for (RunObserver *observer : observers)
          observer->record_uptake(record.time, now, gap);
      }
    return now.dm_total;
  }

  void
  IFEMSimulation::record_flow(const StepReport &report)
  {
    const FlowMeasures m    = fluid.measure();
    const Tensor<1, 3> held = cells.held_force();
    record.flow.add(record.time,
                    m.flow_rate,
                    m.pressure_drop,
                    m.max_velocity,
                    m.divergence_l2,
                    fluid.get_frame_velocity(),
                    report.newton_iterations,
                    report.linear_iterations,
                    held[0],
                    held[1],
                    held[2],
                    m.lab_flow_rate);
  }

  std::vector<CellShape>
  IFEMSimulation::record_shapes()
  {
    const std::vector<CellShape> shapes = cells.shapes();
    const std::vector<CellGaps>  gaps   = measure_gaps(cells.membranes(),
                                                    cells.positions(),
                                                    domain.wall_radius,
                                                    domain.period,
                                                    cells.owners());
    // A gap to nothing (one cell, no wall) is left empty.
    const auto gap_text = [](const double gap) {
      return std::isfinite(gap) ? csv_row(gap) : std::string();
    };
    for (unsigned int c = 0; c < shapes.size(); ++c)
      {
        const CellShape &s = shapes[c];
        record.cells.add(record.time,
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
                         s.inclination,
                         gap_text(gaps[c].to_cells),
                         gap_text(gaps[c].to_wall),
                         s.largest_local_area_change);
      }
    for (RunObserver *observer : observers)
      observer->record(record.time, shapes);
    return shapes;
  }

  std::vector<CellGaps>
  IFEMSimulation::check_gaps(const std::vector<Vector<double>> &last_good)
  {
    std::vector<CellGaps> gaps;
    {
      TimerOutput::Scope scope(timer, "contact check");
      gaps = measure_gaps(cells.membranes(),
                          cells.positions(),
                          domain.wall_radius,
                          domain.period,
                          cells.owners());
    }
    for (unsigned int c = 0; c < gaps.size(); ++c)
      {
        std::ostringstream why;
        if (gaps[c].to_cells < 0.)
          why << "the membrane of cell " << c << " crossed another cell's (gap "
              << gaps[c].to_cells
              << " µm): raise Cell interactions/Repulsion pressure or "
                 "reduce Time/Time step";
        else if (gaps[c].to_wall <= 0.)
          why << "cell " << c << " reached the capillary wall (wall gap "
              << gaps[c].to_wall
              << " µm): set Cell interactions/Wall pressure > 0, or raise it";
        if (!why.str().empty())
          stop(why.str(), last_good);
      }
    return gaps;
  }

  std::pair<double, double>
  IFEMSimulation::smallest_gaps() const
  {
    double cell_gap = std::numeric_limits<double>::infinity();
    double wall_gap = cell_gap;
    for (const CellGaps &gaps : measure_gaps(cells.membranes(),
                                             cells.positions(),
                                             domain.wall_radius,
                                             domain.period,
                                             cells.owners()))
      {
        cell_gap = std::min(cell_gap, gaps.to_cells);
        wall_gap = std::min(wall_gap, gaps.to_wall);
      }
    return {cell_gap, wall_gap};
  }

  double
  IFEMSimulation::smallest_cell_gap() const
  {
    return cells.size() > 1 ? smallest_gaps().first :
                              std::numeric_limits<double>::infinity();
  }

  void
  IFEMSimulation::write_fields()
  {
    TimerOutput::Scope scope(timer, "output");
    const std::string &directory = parameters.output_directory;
    write_together(communicator, [&]() {
      record.fluid_files.emplace_back(
        record.time, fluid.write_vtu(directory, record.step, frame_data()));
      write_pvd(directory, "flow", record.fluid_files, communicator);
      write_membrane_series(cells,
                            parameters.immersed.membrane_files,
                            record,
                            directory,
                            frame_data(),
                            communicator);
    });
  }

  FieldData
  IFEMSimulation::frame_data() const
  {
    return frame_field_data(record.time,
                            fluid.get_frame_velocity(),
                            record.frame_offset);
  }

  void
  IFEMSimulation::write_tables() const
  {
    write_together(communicator, [&]() {
      if (Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      const std::string &directory = parameters.output_directory;
      record.flow.write(directory + "/flow.csv");
      record.cells.write(directory + "/cells.csv");
      if (parameters.immersed.diffusion_interval > 0)
        record.dm.write(directory + "/dm.csv");
      for (const RunObserver *observer : observers)
        observer->write_tables(directory);
    });
  }

  void
  IFEMSimulation::write_checkpoint() const
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    CheckpointState    state;
    state.parameters  = parameter_file_text;
    state.record      = record;
    state.fluid       = fluid.state();
    state.fluid_cells = fluid.cell_values();
    state.positions   = cells.positions();
    for (const RunObserver *observer : observers)
      state.observers.push_back(observer->state());
    write_together(communicator,
                   [&]() { checkpoint.write(state, communicator); });
  }

  void
  IFEMSimulation::read_checkpoint()
  {
    const CheckpointState state = checkpoint.read({parameter_file_text,
                                                   fluid.n_dofs(),
                                                   cells.size(),
                                                   cells.positions()[0].size(),
                                                   parameters.time.n_steps},
                                                  communicator);
    if (state.observers.size() != observers.size())
      throw InputError("Immersed cells/Resume",
                       "true",
                       "the checkpoint " + checkpoint.resumed_from() +
                         " comes from another experiment (it records " +
                         std::to_string(state.observers.size()) +
                         " observer(s), this one " +
                         std::to_string(observers.size()) + ").");
    for (unsigned int i = 0; i < observers.size(); ++i)
      observers[i]->restore(state.observers[i]);
    record = state.record;
    fluid.set_state(state.fluid, fluid_cells_here(state));
    cells.set_positions(state.positions);
    coupling->place(cells.points());
  }

  CellRecords
  IFEMSimulation::fluid_cells_here(const CheckpointState &state) const
  {
    try
      {
        return state.fluid_cells.to_owners(
          fluid.velocity_dof_handler().get_triangulation());
      }
    catch (const std::runtime_error &e)
      {
        throw InputError("Immersed cells/Resume",
                         "true",
                         "the checkpoint " + checkpoint.resumed_from() +
                           " cannot be resumed: " + e.what() + ".");
      }
  }

  void
  IFEMSimulation::save_and_stop(const int signal) const
  {
    write_tables();
    write_checkpoint();
    const std::string &directory = parameters.output_directory;
    throw RunInterrupted(signal,
                         signal_name(signal) + " at step " +
                           std::to_string(record.step) + ", t = " +
                           to_text(record.time) + " s: the tables so far and " +
                           directory + "/checkpoint.bin are written.");
  }

  void
  IFEMSimulation::stop(const std::string                 &why,
                       const std::vector<Vector<double>> &last_good,
                       const bool                         after_step)
  {
    cells.set_positions(last_good);
    write_tables();
    // Each cell by its owner, which alone keeps its membrane.
    cells.write_vtu(parameters.output_directory,
                    "last_good_cell",
                    record.step,
                    frame_data(),
                    communicator);
    const bool full_stop = !why.empty() && why.back() == '.';
    throw SolverFailure(
      "step " + std::to_string(record.step + (after_step ? 0 : 1)) +
      ", t = " + std::to_string(record.time) +
      " s: " + why.substr(0, why.size() - (full_stop ? 1 : 0)) +
      ". The tables so far and the last good membranes (last_good_cell_*.vtu) "
      "are in " +
      parameters.output_directory + ".");
  }

  void
  IFEMSimulation::run()
  {
    if (record.step == 0)
      record_start();
    const InterruptionGuard interruption;
    Timer                   clock;
    const unsigned int      first_step         = record.step;
    const MpiTraffic        traffic_at_start   = MpiTraffic::so_far();
    const unsigned int      handovers_at_start = cells.owners().n_handovers();
    while (record.step < parameters.time.n_steps)
      {
        const StepReport stepped = advance();
        if (const int signal = interruption.received(communicator))
          save_and_stop(signal);
        const StepActions due = schedule.actions(record.step);
        if (due.any())
          do_what_is_due(due, stepped, clock, first_step);
      }
    write_tables();
    run_report.summary(record,
                       cells,
                       record.step - first_step,
                       clock.wall_time());
    report_load_balance();
    run_report.communication(MpiTraffic::so_far() - traffic_at_start,
                             record.step - first_step,
                             cells.owners().n_handovers() - handovers_at_start);
    timer.print_summary();
  }

  void
  IFEMSimulation::report_load_balance() const
  {
    run_report.load_balance(cells,
                            coupling->n_locally_owned_points(),
                            triangulation.n_locally_owned_active_cells());
  }

  void
  IFEMSimulation::record_start()
  {
    record_shapes();
    if (parameters.immersed.diffusion_interval > 0)
      {
        // Solved before the line starts: a solve that stops the run then
        // leaves no half line.
        const double dm = solve_uptake(0);
        pcout << "  t = 0 s: DM " << dm << " µm³/(s Torr)" << std::endl;
      }
    // The tables first: small, and what a full disk should leave whole.
    write_tables();
    write_fields();
  }

  void
  IFEMSimulation::do_what_is_due(const StepActions &due,
                                 const StepReport  &stepped,
                                 const Timer       &clock,
                                 const unsigned int first_step)
  {
    const TimeParameters &time = parameters.time;
    const unsigned int    step = record.step;
    record_flow(stepped);
    std::ostringstream progress;
    progress << "  step " << step << " of " << time.n_steps
             << ", t = " << record.time << " of " << time.n_steps * time_step
             << " s: " << stepped.linear_iterations
             << " FGMRES iterations, frame velocity "
             << fluid.get_frame_velocity() << " µm/s";
    if (due.diffusion)
      progress << ", DM "
               << solve_uptake(step / parameters.immersed.diffusion_interval)
               << " µm³/(s Torr)";
    const std::vector<CellShape> shapes =
      due.output ? record_shapes() : cells.shapes();
    if (cells.size() > 1)
      progress << ", smallest gap between cells " << smallest_cell_gap()
               << " µm";
    progress << "; cell 0: volume change "
             << shapes[0].volume / cells.reference_volume(0) - 1.
             << ", deformation index " << shapes[0].deformation_index;
    for (const RunObserver *observer : observers)
      progress << observer->progress(shapes);
    if (due.output)
      {
        write_tables();
        write_fields();
      }
    pcout << progress.str() << "  "
          << time_left_text(clock.wall_time(),
                            step - first_step,
                            time.n_steps - step)
          << std::endl;
    if (due.checkpoint)
      write_checkpoint();
  }
} // namespace rbc_ifem

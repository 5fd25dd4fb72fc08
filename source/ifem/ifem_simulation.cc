#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/interruption.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/coupling/membrane_forces.h>
#include <rbc_ifem/coupling/semi_implicit_load.h>
#include <rbc_ifem/coupling/time_step_limit.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>
#include <rbc_ifem/ifem/ifem_simulation.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/crc.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// Everything in a checkpoint: the run's parameters and record, the
    /// fluid, the membranes.
    struct Checkpoint
    {
      unsigned int                n_ranks = 0;
      std::string                 parameters; ///< the run's parameters.prm
      RunRecord                   record;
      FluidState                  fluid;
      std::vector<Vector<double>> positions;

      template <class Archive>
      void
      serialize(Archive &archive, const unsigned int)
      {
        archive &n_ranks &parameters &record &fluid &positions;
      }
    };

    /**
     * The file's first lines: what it is, the format of what follows
     * (raised whenever what a checkpoint holds changes, so that an old
     * checkpoint is refused by name, not misread), and the payload's size
     * and CRC-32, so that a truncated or damaged file is refused.
     */
    const std::string  checkpoint_title          = "rbc-ifem checkpoint";
    constexpr unsigned checkpoint_current_format = 20261204;

    std::uint32_t
    crc32(const std::string &bytes)
    {
      boost::crc_32_type crc;
      crc.process_bytes(bytes.data(), bytes.size());
      return crc.checksum();
    }

    /// The checkpoint file's text: its header lines, then @p payload.
    std::string
    checkpoint_file(const std::string &payload)
    {
      std::ostringstream file;
      file << checkpoint_title << "\nformat " << checkpoint_current_format
           << "\nbytes " << payload.size() << "\ncrc32 " << crc32(payload)
           << '\n'
           << payload;
      return file.str();
    }

    /**
     * The payload of the checkpoint file @p path, checked; throws the
     * reason it cannot be used (not a checkpoint, another format,
     * truncated, damaged) as a std::runtime_error.
     */
    std::string
    checkpoint_payload(const std::string &path)
    {
      std::ifstream in(path, std::ios::binary);
      std::string   title, format_word, bytes_word, crc_word;
      unsigned long format = 0, bytes = 0;
      std::uint32_t crc = 0;
      std::getline(in, title);
      if (title != checkpoint_title)
        throw std::runtime_error("it is not an rbc-ifem checkpoint");
      in >> format_word >> format >> bytes_word >> bytes >> crc_word >> crc;
      in.get();
      if (!in || format_word != "format" || bytes_word != "bytes" ||
          crc_word != "crc32")
        throw std::runtime_error("its header is damaged");
      if (format != checkpoint_current_format)
        throw std::runtime_error("it has the format " + std::to_string(format) +
                                 "; this version of rbc-ifem reads " +
                                 std::to_string(checkpoint_current_format));
      std::string payload(bytes, '\0');
      in.read(payload.data(), bytes);
      if (static_cast<unsigned long>(in.gcount()) != bytes)
        throw std::runtime_error(
          "it is truncated: " + std::to_string(in.gcount()) + " of its " +
          std::to_string(bytes) + " bytes are there");
      if (crc32(payload) != crc)
        throw std::runtime_error(
          "it is damaged: the checksum of its contents does not match");
      return payload;
    }

    /// The membranes @p surfaces as the uptake solve takes them.
    std::vector<const Triangulation<2, 3> *>
    pointers_to(
      const std::vector<std::unique_ptr<Triangulation<2, 3>>> &surfaces)
    {
      std::vector<const Triangulation<2, 3> *> pointers;
      for (const auto &surface : surfaces)
        pointers.push_back(surface.get());
      return pointers;
    }

    /// The parameters a resumed run may change: how long it runs and what
    /// it reports, not what it computes.
    bool
    may_change_on_resume(const std::string &name)
    {
      return name == "Output directory" || name == "Time/Number of steps" ||
             name == "Time/Output interval" ||
             name == "Immersed cells/Resume" ||
             name == "Immersed cells/Checkpoint interval" ||
             name == "Immersed cells/Progress interval";
    }
  } // namespace

  IFEMSimulation::IFEMSimulation(const Parameters  &parameters,
                                 const std::string &parameter_file_text,
                                 const FlowDomain  &domain,
                                 const MPI_Comm     communicator,
                                 TimerOutput       &timer)
    : parameters(parameters)
    , parameter_file_text(parameter_file_text)
    , communicator(communicator)
    , domain(domain)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(timer)
    , triangulation(communicator)
    , fluid(triangulation,
            parameters.fluid,
            domain.drive,
            parameters.time.plasma_time_step(),
            timer)
    , cells(domain.placements, parameters.cells, parameters.membrane)
  {
    add_cell_forces();
    contacts = cells.size() > 1 || domain.wall_radius.has_value();

    record.flow.set_header(
      "time,flow_rate,pressure_drop,max_velocity,divergence_l2,"
      "frame_velocity,newton_iterations,linear_iterations,held_force_x,"
      "held_force_y,held_force_z,lab_flow_rate");
    record.cells.set_header(
      "time,cell,x,y,z,area,volume,axial_length,max_radius,deformation_index,"
      "frame_x,volume_change,area_change,taylor_deformation,inclination,"
      "min_gap,wall_gap,local_area_change");
    record.dm.set_header(
      dm_header(cells.size(),
                parameters.diffusion.uptake == CellUptake::reaction));
    record.cell_files.resize(cells.size());
  }

  void
  IFEMSimulation::add_cell_forces()
  {
    const ImmersedParameters &immersed = parameters.immersed;
    if (immersed.tether_stiffness > 0.)
      cells.add_force(
        std::make_unique<Tether>(cells.membranes(), immersed.tether_stiffness));
    const std::vector<Tensor<1, 3>> pushes = immersed.pushing_force_vectors();
    if (!pushes.empty())
      {
        if (pushes.size() != cells.size())
          throw InputError("Immersed cells/Pushing forces",
                           immersed.pushing_forces,
                           "one force 'Fx, Fy, Fz' per cell: " +
                             std::to_string(cells.size()) +
                             " separated by ';', or none.");
        cells.add_force(
          std::make_unique<PushingForce>(cells.membranes(), pushes));
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
    if (parameters.immersed.squeeze_into_lumen)
      {
        TimerOutput::Scope  scope(timer, "squeeze into lumen");
        const WallRepulsion wall(
          cells.membranes(),
          *domain.wall_radius,
          RepulsivePotential(parameters.interactions.wall_pressure,
                             parameters.interactions.wall_range));
        std::vector<Vector<double>> x      = cells.positions();
        const unsigned int          stages = wall.squeeze_into_lumen(x);
        cells.set_positions(x);
        pcout << "  squeezed into the lumen in " << stages << " stages"
              << std::endl;
      }
    // The membranes are replicated; from here on their forces and stiffness
    // are shared out over the ranks, which compute them together. The
    // squeeze above runs on every rank alone, so that its L-BFGS path, and
    // the squeezed shape within its tolerance, are the same for any number
    // of ranks.
    cells.share_work(communicator);
    std::vector<std::shared_ptr<const Triangulation<3>>> coarser_meshes;
    {
      TimerOutput::Scope          scope(timer, "fluid mesh");
      const std::vector<Point<3>> band =
        points_in_segment(cells.points(), domain.period);
      coarser_meshes = create_distributed_mesh_hierarchy(
        triangulation,
        [&](Triangulation<3> &serial) {
          domain.create_mesh(serial);
          if (domain.period)
            add_end_periodicity(serial);
          refine_near_points(serial,
                             band,
                             parameters.mesh.band_width,
                             parameters.mesh.fluid_band_refinements);
        },
        domain.period.has_value());
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
    const CouplingTimeStepLimit stable(parameters.fluid.viscosity,
                                       parameters.membrane,
                                       cells.point_spacing(),
                                       mesh_size);
    time_step = parameters.time.coupled_time_step(stable.limit,
                                                  parameters.immersed.coupling);
    fluid.set_time_step(time_step);
    if (parameters.immersed.coupling == CouplingScheme::semi_implicit)
      setup_semi_implicit_load();

    pcout << "  fluid mesh: " << triangulation.n_global_active_cells()
          << " cells, " << fluid.n_dofs() << " DoFs; "
          << multigrid_levels_text(fluid) << std::endl;
    report_startup(stable);
    if (parameters.immersed.diffusion_interval > 0)
      check_uptake_input();
    if (parameters.immersed.resume)
      {
        read_checkpoint();
        pcout << "  resumed from the checkpoint at step " << record.step
              << ", t = " << record.time << " s" << std::endl;
      }
  }

  void
  IFEMSimulation::report_startup(const CouplingTimeStepLimit &stable) const
  {
    const FluidParameters    &f           = parameters.fluid;
    const MembraneParameters &m           = parameters.membrane;
    const double              speed       = domain.velocity_scale;
    const double              length      = domain.length_scale;
    const double              spacing     = cells.point_spacing();
    const double              stable_step = stable.limit;

    pcout << "  cells: " << cells.size() << ", " << cells.n_points()
          << " membrane points, spacing up to " << spacing
          << " µm; fluid mesh size at the cells h = " << mesh_size << " µm\n"
          << "  Reynolds number ρ U L / μ = "
          << f.density * speed * length / f.viscosity
          << ", capillary number μ U / G = "
          << f.viscosity * speed / m.shear_modulus
          << " (U = " << domain.velocity_symbol
          << ", L = " << domain.length_symbol << ")\n"
          << "  explicit-coupling time step limit ≈ " << stable_step
          << " s (in-plane " << stable.in_plane << " s, bending "
          << stable.bending
          << " s); explicit runs stay stable below about 0.7 of it "
             "(doc/ifem.md); coupling "
          << name_of(parameters.immersed.coupling, coupling_scheme_names())
          << ", Δt = " << time_step << " s ("
          << (parameters.time.automatic_time_step() ? "Time step = auto, " : "")
          << time_step / stable_step << " of the estimate)" << std::endl;
    // Measured (doc/ifem.md): 0.71 of the estimate stable over the default
    // run, 0.83 diverged after 112 steps.
    if (parameters.immersed.coupling == CouplingScheme::explicit_forces &&
        time_step > 0.75 * stable_step)
      pcout << "  WARNING: Time/Time step = " << time_step << " s is "
            << time_step / stable_step << " of the explicit-coupling estimate "
            << stable_step
            << " s; runs stay stable below about 0.7 of it: set it to at "
               "most "
            << 0.7 * stable_step
            << " s, or to auto, or set Immersed cells/Coupling = "
               "semi-implicit."
            << std::endl;
    const InteractionParameters &contact = parameters.interactions;
    if (cells.size() > 1 && contact.repulsion_pressure > 0. &&
        contact.repulsion_range < spacing)
      pcout << "  WARNING: Cell interactions/Repulsion range = "
            << contact.repulsion_range
            << " µm is shorter than the membrane point spacing " << spacing
            << " µm: a point of one cell may slip between the points of "
               "another. Raise the range or Cells/Surface refinements."
            << std::endl;
    if (spacing > 0.5 * mesh_size)
      pcout
        << "  WARNING: the membrane point spacing " << spacing
        << " µm exceeds half the fluid mesh size at the cells, h/2 = "
        << 0.5 * mesh_size
        << " µm (the paper's rule). To follow it, raise Cells/Surface "
           "refinements and Mesh/Diffusion band refinements by one each and "
           "set Time/Time step = auto (closer points lower the explicit-"
           "coupling estimate), or lower Mesh/Fluid band refinements."
        << std::endl;
  }

  void
  IFEMSimulation::setup_semi_implicit_load()
  {
    semi_implicit = std::make_unique<SemiImplicitLoad>(
      *coupling, cells, fluid.velocity_zero_constraints(), time_step);
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
      forces = cells.compute_forces();
    }
    if (parameters.immersed.coupling == CouplingScheme::semi_implicit)
      {
        TimerOutput::Scope scope(timer, "membrane stiffness");
        cells.linearize();
      }
    for (const Tensor<1, 3> &force : forces)
      if (!std::isfinite(force.norm()))
        stop("the membrane forces are not finite", last_good);
    {
      TimerOutput::Scope scope(timer, "coupling: spread");
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
        why << "a membrane point moved " << largest_move
            << " µm in one step, more than "
            << "Immersed cells/Maximum step displacement = "
            << parameters.immersed.max_step_displacement
            << " of the fluid mesh size " << mesh_size << " µm: the "
            << name_of(parameters.immersed.coupling, coupling_scheme_names())
            << " coupling is unstable or the step too long; reduce Time/Time "
               "step = "
            << dt << " s";
        stop(why.str(), last_good);
      }

    cells.move(velocities, dt);
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
      fluid.set_frame_velocity(fluid.get_frame_velocity() +
                               mean_axial_velocity);
    return report;
  }

  void
  IFEMSimulation::check_uptake_input() const
  {
    TimerOutput::Scope scope(timer, "diffusion: input check");
    const auto         surfaces = cells.current_surfaces();
    const auto         mapping  = cells.surface_mapping(surfaces);
    check_uptake_meshes(parameters.geometry,
                        parameters.mesh,
                        parameters.diffusion,
                        pointers_to(surfaces),
                        mapping,
                        parameters.mesh.diffusion_band_refinements,
                        communicator,
                        timer);
  }

  double
  IFEMSimulation::solve_uptake(const unsigned int counter)
  {
    const auto         surfaces  = cells.current_surfaces();
    const auto         mapping   = cells.surface_mapping(surfaces);
    const std::string &directory = parameters.output_directory;
    Uptake             uptake;
    try
      {
        uptake =
          rbc_ifem::solve_uptake(parameters.geometry,
                                 parameters.mesh,
                                 parameters.diffusion,
                                 pointers_to(surfaces),
                                 mapping,
                                 parameters.mesh.diffusion_band_refinements,
                                 communicator,
                                 timer,
                                 [&](const DiffusionSolver &diffusion) {
                                   record.uptake_fields.write(diffusion,
                                                              directory,
                                                              record.time,
                                                              counter,
                                                              communicator,
                                                              frame_data());
                                 });
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
    record.dm.add_row(dm_row(record.time, uptake));
    record.dm_history.emplace_back(record.time, uptake.dm_total);
    if (!observers.empty())
      {
        const double gap = smallest_cell_gap();
        for (RunObserver *observer : observers)
          observer->record_uptake(record.time, uptake, gap);
      }
    return uptake.dm_total;
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
                                                    domain.period);
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
                          domain.period);
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

  double
  IFEMSimulation::smallest_cell_gap() const
  {
    double smallest = std::numeric_limits<double>::infinity();
    if (cells.size() > 1)
      for (const CellGaps &gaps : measure_gaps(cells.membranes(),
                                               cells.positions(),
                                               domain.wall_radius,
                                               domain.period))
        smallest = std::min(smallest, gaps.to_cells);
    return smallest;
  }

  void
  IFEMSimulation::write_fields()
  {
    TimerOutput::Scope scope(timer, "output");
    const std::string &directory = parameters.output_directory;
    record.fluid_files.emplace_back(
      record.time, fluid.write_vtu(directory, record.step, frame_data()));
    write_pvd(directory, "flow", record.fluid_files, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        const std::vector<std::string> files =
          cells.write_vtu(directory, "cell", record.step, frame_data());
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
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const std::string &directory = parameters.output_directory;
    record.flow.write(directory + "/flow.csv");
    record.cells.write(directory + "/cells.csv");
    if (parameters.immersed.diffusion_interval > 0)
      record.dm.write(directory + "/dm.csv");
    for (const RunObserver *observer : observers)
      observer->write_tables(directory);
  }

  void
  IFEMSimulation::write_checkpoint() const
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    Checkpoint         checkpoint;
    checkpoint.n_ranks    = Utilities::MPI::n_mpi_processes(communicator);
    checkpoint.parameters = parameter_file_text;
    checkpoint.record     = record;
    checkpoint.fluid      = fluid.state();
    checkpoint.positions  = cells.positions();
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    std::ostringstream payload;
    {
      boost::archive::binary_oarchive archive(payload);
      archive << checkpoint;
    }
    // The last two: the one before stays as checkpoint_previous.bin.
    const std::string path = parameters.output_directory + "/checkpoint.bin";
    if (std::filesystem::exists(path))
      std::filesystem::rename(path,
                              parameters.output_directory +
                                "/checkpoint_previous.bin");
    const std::string file = checkpoint_file(payload.str());
    write_file_atomically(path, [&](std::ostream &out) { out << file; });
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
        std::istringstream              payload(checkpoint_payload(path));
        boost::archive::binary_iarchive archive(payload);
        archive >> checkpoint;
      }
    catch (const std::exception &e)
      {
        throw InputError("Immersed cells/Resume",
                         "true",
                         "the checkpoint " + path +
                           " cannot be used: " + e.what() +
                           ". The one before it, if the run wrote two, is "
                           "checkpoint_previous.bin: rename it to "
                           "checkpoint.bin to resume from there.");
      }
    check_resumed_parameters(checkpoint.parameters, path);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    if (checkpoint.n_ranks != n_ranks ||
        checkpoint.fluid.solution.size() != fluid.n_dofs() ||
        checkpoint.positions.size() != cells.size() ||
        checkpoint.positions[0].size() != cells.positions()[0].size())
      throw InputError("Immersed cells/Resume",
                       "true",
                       "the checkpoint " + path + " comes from a run on " +
                         std::to_string(checkpoint.n_ranks) + " rank(s) with " +
                         std::to_string(checkpoint.fluid.solution.size()) +
                         " fluid DoFs; this run has " +
                         std::to_string(n_ranks) + " rank(s) and " +
                         std::to_string(fluid.n_dofs()) +
                         ": resume on the same number of ranks.");
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
  IFEMSimulation::check_resumed_parameters(const std::string &written,
                                           const std::string &path) const
  {
    const auto before = parameter_values(written);
    for (const auto &[name, value] : parameter_values(parameter_file_text))
      {
        const auto old = before.find(name);
        if (old != before.end() && old->second != value &&
            !may_change_on_resume(name))
          throw InputError(
            name,
            value,
            "the checkpoint " + path + " was written by a run with " + name +
              " = " + old->second +
              ". A resumed run computes what the run that "
              "wrote it did: only Time/Number of steps, "
              "Time/Output interval, Immersed cells/Resume, "
              "Checkpoint interval and Progress interval may "
              "change (and Output directory, for a copied run).");
      }
  }

  void
  IFEMSimulation::save_and_stop(const int signal) const
  {
    write_tables();
    write_checkpoint();
    const std::string &directory = parameters.output_directory;
    throw RunInterrupted(
      signal,
      signal_name(signal) + " at step " + std::to_string(record.step) +
        ", t = " + to_text(record.time) + " s: the tables so far and " +
        directory +
        "/checkpoint.bin are written. To go on: rbc-ifem FILE.prm " +
        "--set \"Immersed cells/Resume=true\"");
  }

  void
  IFEMSimulation::stop(const std::string                 &why,
                       const std::vector<Vector<double>> &last_good,
                       const bool                         after_step)
  {
    cells.set_positions(last_good);
    write_tables();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      cells.write_vtu(parameters.output_directory,
                      "last_good_cell",
                      record.step,
                      frame_data());
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
  IFEMSimulation::report_summary(const unsigned int n_run,
                                 const double       wall_seconds) const
  {
    pcout << "  summary: t = " << record.time << " s, " << n_run << " steps in "
          << duration_text(wall_seconds) << ", "
          << wall_seconds / std::max(1u, n_run) << " s per step" << std::endl;
    if (!record.dm_history.empty())
      {
        // 1 µm³/s = 6e-11 mL/min, and 1 mmHg = 1.000000142 Torr.
        const double to_ml_min_mmhg    = 60e-12 * 1.000000142;
        const auto [first_time, first] = record.dm_history.front();
        const auto [last_time, last]   = record.dm_history.back();
        if (record.dm_history.size() == 1)
          pcout << "  DM at t = " << first_time << " s " << first
                << " µm³/(s Torr), " << first * to_ml_min_mmhg
                << " mL/(min mmHg)" << std::endl;
        else
          pcout << "  DM at t = " << first_time << " s " << first
                << ", at t = " << last_time << " s " << last
                << " µm³/(s Torr) (" << std::showpos
                << 100. * (last / first - 1.) << std::noshowpos
                << "%); in mL/(min mmHg) " << first * to_ml_min_mmhg << " and "
                << last * to_ml_min_mmhg << std::endl;
      }
    const std::vector<CellShape> shapes = cells.shapes();
    double deformation = 0., volume_drift = 0., area_drift = 0.,
           local_area = 0.;
    for (unsigned int c = 0; c < shapes.size(); ++c)
      {
        local_area = std::max(local_area, shapes[c].largest_local_area_change);
        deformation += shapes[c].deformation_index / shapes.size();
        const double dv = shapes[c].volume / cells.reference_volume(c) - 1.;
        const double da = shapes[c].area / cells.reference_area(c) - 1.;
        volume_drift =
          std::abs(dv) > std::abs(volume_drift) ? dv : volume_drift;
        area_drift = std::abs(da) > std::abs(area_drift) ? da : area_drift;
      }
    pcout << "  cells at the end: deformation index " << deformation
          << (shapes.size() > 1 ? " (mean)" : "") << ", volume change "
          << 100. * volume_drift << "%, area change " << 100. * area_drift
          << "%" << (shapes.size() > 1 ? " (the largest over the cells)" : "")
          << ", largest local area change " << 100. * local_area
          << "% (the cell field area_change of cell_C.pvd)" << std::endl;
  }

  void
  IFEMSimulation::run()
  {
    const ImmersedParameters &immersed = parameters.immersed;
    const TimeParameters     &time     = parameters.time;
    const auto due = [](const unsigned int step, const unsigned int interval) {
      return interval > 0 && step % interval == 0;
    };
    if (record.step == 0)
      {
        record_shapes();
        if (immersed.diffusion_interval > 0)
          {
            const double dm = solve_uptake(0);
            pcout << "  t = 0 s: DM " << dm << " µm³/(s Torr)" << std::endl;
          }
        write_fields();
        write_tables();
      }

    const InterruptionGuard interruption;
    Timer                   clock;
    const unsigned int      first_step = record.step;
    const double            end_time   = time.n_steps * time_step;
    while (record.step < time.n_steps)
      {
        const StepReport report = advance();
        if (const int signal = interruption.received(communicator))
          save_and_stop(signal);
        const unsigned int step      = record.step;
        const bool         last      = step == time.n_steps;
        const bool         diffusion = due(step, immersed.diffusion_interval);
        const bool         output    = due(step, time.output_interval) || last;
        if (!(diffusion || output || due(step, immersed.progress_interval) ||
              due(step, immersed.checkpoint_interval)))
          continue;

        record_flow(report);
        std::ostringstream progress;
        progress << "  step " << step << " of " << time.n_steps
                 << ", t = " << record.time << " of " << end_time
                 << " s: " << report.linear_iterations
                 << " FGMRES iterations, frame velocity "
                 << fluid.get_frame_velocity() << " µm/s";
        if (diffusion)
          progress << ", DM "
                   << solve_uptake(step / immersed.diffusion_interval)
                   << " µm³/(s Torr)";
        const std::vector<CellShape> shapes =
          output ? record_shapes() : cells.shapes();
        if (cells.size() > 1)
          progress << ", smallest gap between cells " << smallest_cell_gap()
                   << " µm";
        progress << "; cell 0: volume change "
                 << shapes[0].volume / cells.reference_volume(0) - 1.
                 << ", deformation index " << shapes[0].deformation_index;
        for (const RunObserver *observer : observers)
          progress << observer->progress(shapes);
        if (output)
          {
            write_fields();
            write_tables();
          }
        pcout << progress.str() << "  "
              << time_left_text(clock.wall_time(),
                                step - first_step,
                                time.n_steps - step)
              << std::endl;
        if (due(step, immersed.checkpoint_interval) ||
            (last && immersed.checkpoint_interval > 0))
          write_checkpoint();
      }
    write_tables();
    report_summary(record.step - first_step, clock.wall_time());
    timer.print_summary();
  }
} // namespace rbc_ifem

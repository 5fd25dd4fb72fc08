#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/fluid/stokes_operator.h>
#include <rbc_ifem/fluid/stokes_preconditioner.h>
#include <rbc_ifem/fluid/velocity_multigrid.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// scale (v(p) - U e_x): a drive's velocity (the first three components
    /// of its (v, p)) seen from a frame moving with U.
    class FrameVelocity : public Function<3>
    {
    public:
      FrameVelocity(const Function<3> &velocity,
                    const double       frame_velocity,
                    const double       scale)
        : Function<3>(3)
        , velocity(velocity)
        , frame_velocity(frame_velocity)
        , scale(scale)
      {}

      double
      value(const Point<3> &p, const unsigned int component) const override
      {
        return scale * (velocity.value(p, component) -
                        (component == 0 ? frame_velocity : 0.));
      }

    private:
      const Function<3> &velocity;
      const double       frame_velocity, scale;
    };

    /// The field "lab_velocity" of the output: the velocity v the frame
    /// sees plus the frame's own, V e_x, i.e. the plasma's velocity in the
    /// laboratory (the capillary wall at rest).
    class LabVelocity : public DataPostprocessorVector<3>
    {
    public:
      explicit LabVelocity(const double frame_velocity)
        : DataPostprocessorVector<3>("lab_velocity", update_values)
        , frame_velocity(frame_velocity)
      {}

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<3> &inputs,
                            std::vector<Vector<double>> &lab) const override
      {
        for (unsigned int q = 0; q < inputs.solution_values.size(); ++q)
          for (unsigned int d = 0; d < 3; ++d)
            lab[q][d] =
              inputs.solution_values[q][d] + (d == 0 ? frame_velocity : 0.);
      }

    private:
      const double frame_velocity;
    };

    /// J + L of FluidProblem: the Stokes operator and the velocity load.
    template <typename Load>
    class OperatorWithLoad
    {
    public:
      OperatorWithLoad(const StokesOperator &stokes, const Load &load)
        : stokes(stokes)
        , load(load)
      {}

      void
      vmult(FluidVector &dst, const FluidVector &src) const
      {
        stokes.vmult(dst, src);
        load(src.block(0), dst.block(0));
      }

    private:
      const StokesOperator &stokes;
      const Load           &load;
    };

    /// The periodic face pairs of a periodic segment on @p dof_handler.
    std::vector<GridTools::PeriodicFacePair<DoFHandler<3>::cell_iterator>>
    periodic_face_pairs(const DoFHandler<3> &dof_handler)
    {
      std::vector<GridTools::PeriodicFacePair<DoFHandler<3>::cell_iterator>>
        pairs;
      GridTools::collect_periodic_faces(dof_handler,
                                        FluidBoundary::inlet,
                                        FluidBoundary::outlet,
                                        /*direction=*/0,
                                        pairs);
      return pairs;
    }
  } // namespace


  FluidProblem::FluidProblem(const Triangulation<3> &triangulation,
                             const FluidParameters  &parameters,
                             const FlowDrive        &drive,
                             const double            time_step,
                             TimerOutput            &timer)
    : parameters(parameters)
    , drive(drive)
    , time_step(time_step)
    , communicator(triangulation.get_communicator())
    , timer(timer)
    , triangulation(triangulation)
    , mapping(2)
    , level_mapping(2)
    , velocity_fe(FE_Q<3>(2), 3)
    , pressure_fe(1)
    , velocity_dofs(triangulation)
    , pressure_dofs(triangulation)
    , frame_velocity(parameters.frame_velocity)
  {}

  FluidProblem::~FluidProblem() = default;

  void
  FluidProblem::setup(
    const std::vector<std::shared_ptr<const Triangulation<3>>> &levels)
  {
    TimerOutput::Scope scope(timer, "fluid: setup");
    setup_dofs();
    setup_solver(levels);
  }

  void
  FluidProblem::setup_dofs()
  {
    mapping.initialize(level_mapping, triangulation);
    velocity_dofs.distribute_dofs(velocity_fe);
    pressure_dofs.distribute_dofs(pressure_fe);
    make_velocity_constraints(mapping, velocity_dofs, velocity_constraints, 0.);
    make_pressure_constraints();
    constrained_frame_velocity = std::numeric_limits<double>::quiet_NaN();
  }

  void
  FluidProblem::make_velocity_constraints(
    const Mapping<3>          &dof_mapping,
    const DoFHandler<3>       &dof_handler,
    AffineConstraints<double> &constraints,
    const double               scale) const
  {
    constraints.clear();
    constraints.reinit(DoFTools::extract_locally_relevant_dofs(dof_handler));
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    for (const auto &[boundary, velocity] : drive.dirichlet)
      VectorTools::interpolate_boundary_values(dof_mapping,
                                               dof_handler,
                                               boundary,
                                               FrameVelocity(*velocity,
                                                             frame_velocity,
                                                             scale),
                                               constraints);
    // After the wall's values, which the periodicity then leaves alone on
    // the edges where the wall meets the ends.
    if (drive.period)
      DoFTools::make_periodicity_constraints<3, 3>(
        periodic_face_pairs(dof_handler), constraints);
    constraints.close();
  }

  void
  FluidProblem::make_pressure_constraints()
  {
    pressure_constraints.clear();
    pressure_constraints.reinit(
      DoFTools::extract_locally_relevant_dofs(pressure_dofs));
    DoFTools::make_hanging_node_constraints(pressure_dofs,
                                            pressure_constraints);
    if (drive.period)
      DoFTools::make_periodicity_constraints<3, 3>(
        periodic_face_pairs(pressure_dofs), pressure_constraints);
    pressure_constraints.close();
  }

  void
  FluidProblem::setup_solver(
    const std::vector<std::shared_ptr<const Triangulation<3>>> &levels)
  {
    stokes = std::make_unique<StokesOperator>(mapping,
                                              velocity_dofs,
                                              pressure_dofs,
                                              velocity_constraints,
                                              pressure_constraints);
    stokes->set_coefficients(parameters.density,
                             parameters.viscosity,
                             time_step);

    AssertThrow(
      !levels.empty() || triangulation.n_global_levels() == 1 ||
        dynamic_cast<const parallel::DistributedTriangulationBase<3> *>(
          &triangulation) == nullptr,
      ExcMessage("A distributed fluid mesh needs its coarser "
                 "meshes (create_distributed_mesh_hierarchy())."));
    coarser_meshes =
      levels.empty() ? global_coarsening_sequence(triangulation) : levels;
    velocity_multigrid = std::make_unique<VelocityMultigrid>(
      coarser_meshes,
      level_mapping,
      stokes->get_matrix_free(),
      StokesOperator::velocity_index,
      velocity_constraints,
      [this](const DoFHandler<3>       &dof_handler,
             AffineConstraints<double> &constraints) {
        make_velocity_constraints(level_mapping, dof_handler, constraints, 0.);
      });
    velocity_multigrid->set_coefficients(parameters.density / time_step,
                                         parameters.viscosity);
    preconditioner =
      std::make_unique<StokesPreconditioner>(*stokes, *velocity_multigrid);

    stokes->initialize_dof_vector(current);
    stokes->initialize_dof_vector(residual);
    stokes->initialize_dof_vector(update);
    initialize_velocity_vector(previous_velocity);
    initialize_velocity_vector(body_force);
    initialize_velocity_vector(load_field);
    initialize_velocity_vector(drive_load);
    initialize_velocity_vector(unit_axial_velocity);
    if (drive.pressure_gradient != 0.)
      stokes->add_uniform_force(Tensor<1, 3>({drive.pressure_gradient, 0., 0.}),
                                drive_load);
    VectorTools::interpolate(mapping,
                             velocity_dofs,
                             Functions::ConstantFunction<3>(
                               std::vector<double>{1., 0., 0.}),
                             unit_axial_velocity);
  }

  void
  FluidProblem::initialize_velocity_vector(VelocityVector &v) const
  {
    stokes->get_matrix_free()->initialize_dof_vector(
      v, StokesOperator::velocity_index);
  }

  double
  FluidProblem::assemble_residual(const bool with_convection)
  {
    TimerOutput::Scope scope(timer, "fluid: residual");
    stokes->residual(residual, current, previous_velocity, with_convection);
    residual.block(0) -= body_force;
    residual.block(0) -= drive_load;
    if (velocity_load)
      velocity_load(current.block(0), residual.block(0));
    return residual.l2_norm();
  }

  void
  FluidProblem::set_velocity_load(const VelocityLoad &load)
  {
    velocity_load = load;
  }

  void
  FluidProblem::add_field_load(const VelocityVector &v,
                               VelocityVector       &result) const
  {
    load_field.copy_locally_owned_data_from(v);
    velocity_constraints.distribute(load_field);
    load_field.update_ghost_values();
    velocity_load(load_field, result);
  }

  std::pair<unsigned int, double>
  FluidProblem::solve_linear_system()
  {
    TimerOutput::Scope scope(timer, "fluid: solve");
    // The tolerance is relative to the largest residual seen, the scale of
    // the problem, not to this step's: a step that changes little then
    // costs few iterations.
    residual_scale = std::max(residual_scale, residual.l2_norm());
    SolverControl             control(parameters.max_linear_iterations,
                          parameters.linear_tolerance * residual_scale);
    SolverFGMRES<FluidVector> solver(
      control, SolverFGMRES<FluidVector>::AdditionalData(100));
    update = 0.;
    residual *= -1.;
    try
      {
        if (velocity_load)
          {
            const auto load = [this](const VelocityVector &v,
                                     VelocityVector       &result) {
              add_field_load(v, result);
            };
            solver.solve(OperatorWithLoad<decltype(load)>(*stokes, load),
                         update,
                         residual,
                         *preconditioner);
          }
        else
          solver.solve(*stokes, update, residual, *preconditioner);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        std::ostringstream message;
        message << "the fluid solver (FGMRES) did not converge: residual "
                << e.last_residual << " after " << e.last_step
                << " iterations, wanted " << control.tolerance()
                << " (Fluid/Max linear iterations = "
                << parameters.max_linear_iterations
                << ", Fluid/Linear solver tolerance = "
                << parameters.linear_tolerance << ")";
        throw SolverFailure(message.str());
      }
    velocity_constraints.distribute(update.block(0));
    pressure_constraints.distribute(update.block(1));
    current.zero_out_ghost_values();
    current += update;
    current.update_ghost_values();
    return {control.last_step(), control.last_value()};
  }

  void
  FluidProblem::apply_step_constraints(FluidVector &state)
  {
    if (frame_velocity != constrained_frame_velocity)
      {
        make_velocity_constraints(mapping,
                                  velocity_dofs,
                                  boundary_constraints,
                                  1.);
        constrained_frame_velocity = frame_velocity;
      }
    boundary_constraints.distribute(state.block(0));
    pressure_constraints.distribute(state.block(1));
    state.update_ghost_values();
  }

  double
  FluidProblem::start_step(const bool with_convection)
  {
    // vⁿ with this step's boundary values, and, from the second step on,
    // the extrapolation 2 vⁿ - vⁿ⁻¹: whichever has the smaller residual
    // starts the solve. A flow driven by slowly changing forces (a
    // deforming cell, the semi-implicit coupling's implicit force) changes
    // smoothly, and the extrapolation saves a third to a half of the
    // iterations; a flow starting from rest does not, and keeps vⁿ. A
    // residual costs about one FGMRES iteration's tenth.
    current.zero_out_ghost_values();
    if (extrapolated.size() == 0)
      {
        extrapolated.reinit(current);
        extrapolated_residual.reinit(residual);
      }
    const bool extrapolate = earlier.size() > 0;
    if (extrapolate)
      {
        extrapolated.copy_locally_owned_data_from(current);
        extrapolated.sadd(2., -1., earlier);
      }
    else
      earlier.reinit(current);
    earlier.copy_locally_owned_data_from(current);

    apply_step_constraints(current);
    const double kept = assemble_residual(with_convection);
    if (!extrapolate)
      return kept;
    apply_step_constraints(extrapolated);
    current.swap(extrapolated);
    residual.swap(extrapolated_residual);
    const double extrapolated_norm = assemble_residual(with_convection);
    if (extrapolated_norm < kept)
      return extrapolated_norm;
    current.swap(extrapolated);
    residual.swap(extrapolated_residual);
    return kept;
  }

  StepReport
  FluidProblem::advance()
  {
    previous_velocity.copy_locally_owned_data_from(current.block(0));
    previous_velocity.update_ghost_values();
    const bool navier_stokes = parameters.model == FluidModel::navier_stokes;
    StepReport report;
    const auto check_finite = [&](const double r) {
      if (!std::isfinite(r))
        throw SolverFailure(
          "the fluid residual is not finite: the flow solution has diverged");
      report.residuals.push_back(r);
      return r;
    };

    const double first    = check_finite(start_step(navier_stokes));
    report.final_residual = first;
    if (first <= parameters.linear_tolerance * residual_scale)
      return report;
    if (!navier_stokes)
      {
        // Linear: one solve with the Stokes operator is exact.
        const auto [iterations, linear_residual] = solve_linear_system();
        report.linear_iterations                 = iterations;
        report.final_residual                    = linear_residual;
        report.newton_iterations                 = 1;
        return report;
      }

    for (double r = first;
         r > parameters.newton_tolerance * std::max(first, residual_scale);)
      {
        if (report.newton_iterations == parameters.max_newton_iterations)
          {
            std::ostringstream message;
            message
              << "Newton did not converge in Fluid/Max Newton iterations = "
              << parameters.max_newton_iterations << ": residuals";
            for (const double residual_norm : report.residuals)
              message << ' ' << std::scientific << std::setprecision(2)
                      << residual_norm;
            throw SolverFailure(message.str());
          }
        stokes->set_convection(current);
        const unsigned int iterations = solve_linear_system().first;
        report.linear_iterations += iterations;
        ++report.newton_iterations;
        r                     = check_finite(assemble_residual(true));
        report.final_residual = r;
      }
    stokes->clear_convection();
    return report;
  }

  void
  FluidProblem::set_time_step(const double new_time_step)
  {
    if (new_time_step == time_step)
      return;
    time_step = new_time_step;
    if (stokes)
      {
        stokes->set_coefficients(parameters.density,
                                 parameters.viscosity,
                                 time_step);
        velocity_multigrid->set_coefficients(parameters.density / time_step,
                                             parameters.viscosity);
      }
  }

  void
  FluidProblem::set_frame_velocity(const double velocity)
  {
    if (velocity == frame_velocity)
      return;
    if (current.size() > 0)
      {
        current.zero_out_ghost_values();
        current.block(0).add(frame_velocity - velocity, unit_axial_velocity);
        current.update_ghost_values();
      }
    if (earlier.size() > 0)
      earlier.block(0).add(frame_velocity - velocity, unit_axial_velocity);
    frame_velocity = velocity;
  }

  double
  FluidProblem::get_frame_velocity() const
  {
    return frame_velocity;
  }

  void
  FluidProblem::set_body_force(const VelocityVector &load)
  {
    body_force.copy_locally_owned_data_from(load);
  }

  FlowMeasures
  FluidProblem::measure() const
  {
    TimerOutput::Scope scope(timer, "fluid: measures");
    FlowMeasures       measures;
    measure_divergence_and_speed(measures);
    measure_flow_through_ends(measures);
    return measures;
  }

  void
  FluidProblem::measure_divergence_and_speed(FlowMeasures &measures) const
  {
    const FEValuesExtractors::Vector velocities(0);
    const QGauss<3>                  quadrature(3);
    FEValues<3>                      fe_values(mapping,
                          velocity_fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
    std::vector<Tensor<1, 3>>        v(quadrature.size());
    std::vector<double>              div_v(quadrature.size());

    double divergence_squared = 0.;
    for (const auto &cell : velocity_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current.block(0), v);
          fe_values[velocities].get_function_divergences(current.block(0),
                                                         div_v);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              divergence_squared += div_v[q] * div_v[q] * fe_values.JxW(q);
              measures.max_velocity =
                std::max(measures.max_velocity, v[q].norm());
            }
        }
    measures.divergence_l2 =
      std::sqrt(Utilities::MPI::sum(divergence_squared, communicator));
    measures.max_velocity =
      Utilities::MPI::max(measures.max_velocity, communicator);
  }

  void
  FluidProblem::measure_flow_through_ends(FlowMeasures &measures) const
  {
    const FEValuesExtractors::Vector velocities(0);
    const QGauss<2>                  face_quadrature(3);
    FEFaceValues<3>                  face_values(mapping,
                                velocity_fe,
                                face_quadrature,
                                update_values | update_normal_vectors |
                                  update_JxW_values);
    FEFaceValues<3>                  pressure_face_values(mapping,
                                         pressure_fe,
                                         face_quadrature,
                                         update_values);
    std::vector<Tensor<1, 3>>        v_face(face_quadrature.size());
    std::vector<double>              p_face(face_quadrature.size());

    // Integrals of p and of 1 over the inlet and the outlet.
    double inlet_pressure = 0., inlet_area = 0., outlet_pressure = 0.,
           outlet_area = 0.;
    for (const auto &cell : velocity_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              (cell->face(f)->boundary_id() == FluidBoundary::inlet ||
               cell->face(f)->boundary_id() == FluidBoundary::outlet))
            {
              const bool outlet =
                cell->face(f)->boundary_id() == FluidBoundary::outlet;
              face_values.reinit(cell, f);
              pressure_face_values.reinit(
                DoFHandler<3>::active_cell_iterator(
                  &triangulation, cell->level(), cell->index(), &pressure_dofs),
                f);
              face_values[velocities].get_function_values(current.block(0),
                                                          v_face);
              pressure_face_values.get_function_values(current.block(1),
                                                       p_face);
              for (const unsigned int q :
                   face_values.quadrature_point_indices())
                {
                  const double JxW = face_values.JxW(q);
                  (outlet ? outlet_pressure : inlet_pressure) +=
                    p_face[q] * JxW;
                  (outlet ? outlet_area : inlet_area) += JxW;
                  if (outlet)
                    measures.flow_rate +=
                      v_face[q] * face_values.normal_vector(q) * JxW;
                }
            }
    measures.flow_rate = Utilities::MPI::sum(measures.flow_rate, communicator);
    // The outlet's normal is e_x: the frame's motion adds V times its area.
    measures.lab_flow_rate =
      measures.flow_rate +
      frame_velocity * Utilities::MPI::sum(outlet_area, communicator);
    measures.pressure_drop =
      Utilities::MPI::sum(inlet_pressure, communicator) /
        Utilities::MPI::sum(inlet_area, communicator) -
      Utilities::MPI::sum(outlet_pressure, communicator) /
        Utilities::MPI::sum(outlet_area, communicator);
    if (drive.period)
      measures.pressure_drop += drive.pressure_gradient * *drive.period;
  }

  std::string
  FluidProblem::write_vtu(const std::string &directory,
                          const unsigned int counter,
                          const FieldData   &field_data) const
  {
    TimerOutput::Scope             scope(timer, "fluid: output");
    const std::vector<std::string> names(3, "velocity");
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(3,
                     DataComponentInterpretation::component_is_part_of_vector);

    const LabVelocity lab_velocity(frame_velocity);
    DataOut<3>        data_out;
    data_out.set_flags(fast_vtk_flags());
    data_out.attach_triangulation(triangulation);
    data_out.add_data_vector(velocity_dofs,
                             current.block(0),
                             names,
                             interpretation);
    data_out.add_data_vector(pressure_dofs, current.block(1), "pressure");
    data_out.add_data_vector(velocity_dofs, current.block(0), lab_velocity);
    data_out.build_patches(mapping, 2);
    return write_vtu_pieces(
      data_out, directory, "flow", counter, communicator, field_data);
  }

  const FluidVector &
  FluidProblem::solution() const
  {
    return current;
  }

  const DoFHandler<3> &
  FluidProblem::velocity_dof_handler() const
  {
    return velocity_dofs;
  }

  const DoFHandler<3> &
  FluidProblem::pressure_dof_handler() const
  {
    return pressure_dofs;
  }

  types::global_dof_index
  FluidProblem::n_dofs() const
  {
    return velocity_dofs.n_dofs() + pressure_dofs.n_dofs();
  }

  const MappingQ<3> &
  FluidProblem::get_mapping() const
  {
    return mapping;
  }

  const MappingQ<3> &
  FluidProblem::get_level_mapping() const
  {
    return level_mapping;
  }

  VelocityMultigrid &
  FluidProblem::velocity_levels()
  {
    return *velocity_multigrid;
  }

  const AffineConstraints<double> &
  FluidProblem::velocity_zero_constraints() const
  {
    return velocity_constraints;
  }

  std::vector<types::global_dof_index>
  FluidProblem::multigrid_dofs() const
  {
    return velocity_multigrid->n_dofs_per_level();
  }

  std::string
  multigrid_levels_text(const FluidProblem &fluid)
  {
    const std::vector<types::global_dof_index> n_dofs = fluid.multigrid_dofs();
    std::ostringstream                         text;
    text << "velocity multigrid: " << n_dofs.size() << " levels of";
    for (unsigned int l = 0; l < n_dofs.size(); ++l)
      text << (l == 0 ? " " : ", ") << n_dofs[l];
    text << " DoFs";
    return text.str();
  }
} // namespace rbc_ifem

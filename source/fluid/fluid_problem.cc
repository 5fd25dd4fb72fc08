#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/fluid/stokes_preconditioner.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/block_sparsity_pattern.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
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
    const FEValuesExtractors::Vector velocities(0);
    const FEValuesExtractors::Scalar pressure(3);
  } // namespace

  PoiseuilleFlow::PoiseuilleFlow(const double              mean_speed,
                                 const double              frame_velocity,
                                 const double              viscosity,
                                 const GeometryParameters &geometry)
    : Function<3>(4)
    , mean_speed(mean_speed)
    , frame_velocity(frame_velocity)
    , viscosity(viscosity)
    , radius(geometry.capillary_radius)
    , length(geometry.capillary_length)
  {}

  double
  PoiseuilleFlow::value(const Point<3> &p, const unsigned int component) const
  {
    const double r2 = (p[1] * p[1] + p[2] * p[2]) / (radius * radius);
    switch (component)
      {
        case 0:
          return 2. * mean_speed * (1. - r2) - frame_velocity;
        case 3:
          return 8. * viscosity * mean_speed * (length - p[0]) /
                 (radius * radius);
        default:
          return 0.;
      }
  }


  SimpleShearFlow::SimpleShearFlow(const double shear_rate)
    : Function<3>(4)
    , shear_rate(shear_rate)
  {}

  double
  SimpleShearFlow::value(const Point<3> &p, const unsigned int component) const
  {
    return component == 0 ? shear_rate * p[1] : 0.;
  }


  FlowDrive
  FlowDrive::capillary(const FluidParameters    &fluid,
                       const GeometryParameters &geometry)
  {
    if (geometry.periodic)
      return periodic_capillary(fluid, geometry);
    FlowDrive drive;
    drive.dirichlet[FluidBoundary::wall] =
      std::make_shared<Functions::ZeroFunction<3>>(4);
    drive.dirichlet[FluidBoundary::inlet] = std::make_shared<PoiseuilleFlow>(
      fluid.inlet_mean_speed, 0., fluid.viscosity, geometry);
    return drive;
  }

  FlowDrive
  FlowDrive::periodic_capillary(const FluidParameters    &fluid,
                                const GeometryParameters &geometry)
  {
    FlowDrive drive;
    drive.dirichlet[FluidBoundary::wall] =
      std::make_shared<Functions::ZeroFunction<3>>(4);
    drive.period        = geometry.capillary_length;
    const double radius = geometry.capillary_radius;
    drive.pressure_gradient =
      8. * fluid.viscosity * fluid.inlet_mean_speed / (radius * radius);
    return drive;
  }

  FlowDrive
  FlowDrive::shear(const double shear_rate)
  {
    FlowDrive drive;
    drive.dirichlet[FluidBoundary::wall] =
      std::make_shared<SimpleShearFlow>(shear_rate);
    return drive;
  }


  namespace
  {
    /// scale (v(p) - U e_x): a drive's velocity seen from a frame moving with
    /// U.
    class FrameVelocity : public Function<3>
    {
    public:
      FrameVelocity(const Function<3> &velocity,
                    const double       frame_velocity,
                    const double       scale)
        : Function<3>(4)
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
  } // namespace


  FluidProblem::FluidProblem(
    const parallel::shared::Triangulation<3> &triangulation,
    const FluidParameters                    &parameters,
    const FlowDrive                          &drive,
    const double                              time_step,
    TimerOutput                              &timer)
    : parameters(parameters)
    , drive(drive)
    , time_step(time_step)
    , communicator(triangulation.get_communicator())
    , timer(timer)
    , triangulation(triangulation)
    , mapping(2)
    , fe(FE_Q<3>(2), 3, FE_Q<3>(1), 1)
    , dof_handler(triangulation)
    , frame_velocity(parameters.frame_velocity)
  {}

  void
  FluidProblem::setup()
  {
    TimerOutput::Scope scope(timer, "fluid: setup");
    setup_dofs();
    setup_matrices();
    assemble_drive_load();
    if (parameters.model == FluidModel::stokes)
      {
        // The Stokes operator does not change: assemble it and its
        // preconditioner once.
        assemble_jacobian(false);
        build_preconditioner();
      }
  }

  void
  FluidProblem::setup_dofs()
  {
    dof_handler.distribute_dofs(fe);
    const std::vector<unsigned int> block_component{0, 0, 0, 1};
    DoFRenumbering::component_wise(dof_handler, block_component);
    const std::vector<types::global_dof_index> dofs_per_block =
      DoFTools::count_dofs_per_fe_block(dof_handler, block_component);
    const types::global_dof_index n_v = dofs_per_block[0],
                                  n_p = dofs_per_block[1];

    const IndexSet owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    owned = {owned_dofs.get_view(0, n_v), owned_dofs.get_view(n_v, n_v + n_p)};
    relevant = {relevant_dofs.get_view(0, n_v),
                relevant_dofs.get_view(n_v, n_v + n_p)};

    if (drive.period)
      GridTools::collect_periodic_faces(dof_handler,
                                        FluidBoundary::inlet,
                                        FluidBoundary::outlet,
                                        /*direction=*/0,
                                        periodic_faces);
    make_constraints(homogeneous_constraints, 0.);
    constrained_frame_velocity = std::numeric_limits<double>::quiet_NaN();
  }

  void
  FluidProblem::make_constraints(AffineConstraints<double> &constraints,
                                 const double               scale) const
  {
    constraints.clear();
    constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);

    const ComponentMask velocity_mask = fe.component_mask(velocities);
    for (const auto &[boundary, velocity] : drive.dirichlet)
      VectorTools::interpolate_boundary_values(mapping,
                                               dof_handler,
                                               boundary,
                                               FrameVelocity(*velocity,
                                                             frame_velocity,
                                                             scale),
                                               constraints,
                                               velocity_mask);
    // After the wall's values, which the periodicity then leaves alone on
    // the edges where the wall meets the ends.
    DoFTools::make_periodicity_constraints<3, 3>(periodic_faces, constraints);
    constraints.close();
  }

  void
  FluidProblem::setup_matrices()
  {
    const unsigned int rank   = Utilities::MPI::this_mpi_process(communicator);
    const auto         reinit = [&](TrilinosWrappers::BlockSparseMatrix &matrix,
                            const auto                          &couples) {
      Table<2, DoFTools::Coupling> coupling(4, 4);
      for (unsigned int c = 0; c < 4; ++c)
        for (unsigned int d = 0; d < 4; ++d)
          coupling[c][d] = couples(c, d) ? DoFTools::always : DoFTools::none;
      TrilinosWrappers::BlockSparsityPattern sparsity(owned,
                                                      owned,
                                                      relevant,
                                                      communicator);
      DoFTools::make_sparsity_pattern(
        dof_handler, coupling, sparsity, homogeneous_constraints, false, rank);
      sparsity.compress();
      matrix.reinit(sparsity);
    };
    // The viscous term μ∇v:∇w couples no two velocity components; only
    // the convective term of Navier-Stokes does. Leaving those couplings
    // out in Stokes mode makes the velocity block, and every AMG and
    // matrix-vector product on it, three times smaller.
    const bool navier_stokes = parameters.model == FluidModel::navier_stokes;
    reinit(system_matrix, [&](unsigned int c, unsigned int d) {
      return (c < 3 && d < 3) ? (c == d || navier_stokes) : (c < 3 || d < 3);
    });
    reinit(schur_matrix,
           [](unsigned int c, unsigned int d) { return c == 3 && d == 3; });

    current.reinit(owned, relevant, communicator);
    previous.reinit(owned, relevant, communicator);
    residual.reinit(owned, communicator);
    update.reinit(owned, communicator);
    body_force.reinit(owned, communicator);
    load_owned.reinit(owned, communicator);
    load_ghosted.reinit(owned, relevant, communicator);
    drive_load.reinit(owned, communicator);
    unit_axial_velocity.reinit(owned, communicator);
    VectorTools::interpolate(mapping,
                             dof_handler,
                             Functions::ConstantFunction<3>(
                               std::vector<double>{1., 0., 0., 0.}),
                             unit_axial_velocity);
  }

  void
  FluidProblem::assemble_jacobian(const bool with_convection)
  {
    TimerOutput::Scope scope(timer, "fluid: assemble Jacobian");
    system_matrix = 0.;
    schur_matrix  = 0.;

    const double       rho = parameters.density, mu = parameters.viscosity;
    const QGauss<3>    quadrature(fe.degree + 1);
    FEValues<3>        fe_values(mapping,
                          fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n, n), cell_schur(n, n);
    std::vector<types::global_dof_index> dof_indices(n);
    std::vector<Tensor<1, 3>>            phi_v(n), v(quadrature.size());
    std::vector<Tensor<2, 3>> grad_phi_v(n), grad_v(quadrature.size());
    std::vector<double>       div_phi_v(n), phi_p(n);
    std::vector<unsigned int> component(n);
    for (unsigned int k = 0; k < n; ++k)
      component[k] = fe.system_to_component_index(k).first;

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0.;
          cell_schur  = 0.;
          if (with_convection)
            {
              fe_values[velocities].get_function_values(current, v);
              fe_values[velocities].get_function_gradients(current, grad_v);
            }
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              for (unsigned int k = 0; k < n; ++k)
                {
                  phi_v[k]      = fe_values[velocities].value(k, q);
                  grad_phi_v[k] = fe_values[velocities].gradient(k, q);
                  div_phi_v[k]  = fe_values[velocities].divergence(k, q);
                  phi_p[k]      = fe_values[pressure].value(k, q);
                }
              const double JxW = fe_values.JxW(q);
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < n; ++j)
                  {
                    const unsigned int ci = component[i], cj = component[j];
                    if (ci == 3 && cj == 3)
                      cell_schur(i, j) += phi_p[i] * phi_p[j] * JxW;
                    else if (ci == 3)
                      cell_matrix(i, j) -= mu * phi_p[i] * div_phi_v[j] * JxW;
                    else if (cj == 3)
                      cell_matrix(i, j) -= div_phi_v[i] * phi_p[j] * JxW;
                    else if (with_convection)
                      cell_matrix(i, j) +=
                        (rho / time_step * (phi_v[j] * phi_v[i]) +
                         mu * scalar_product(grad_phi_v[j], grad_phi_v[i]) +
                         rho * ((grad_phi_v[j] * v[q] + grad_v[q] * phi_v[j]) *
                                phi_v[i])) *
                        JxW;
                    else if (ci == cj)
                      cell_matrix(i, j) +=
                        (rho / time_step * (phi_v[j] * phi_v[i]) +
                         mu * scalar_product(grad_phi_v[j], grad_phi_v[i])) *
                        JxW;
                  }
            }
          cell->get_dof_indices(dof_indices);
          homogeneous_constraints.distribute_local_to_global(cell_matrix,
                                                             dof_indices,
                                                             system_matrix);
          homogeneous_constraints.distribute_local_to_global(cell_schur,
                                                             dof_indices,
                                                             schur_matrix);
        }
    system_matrix.compress(VectorOperation::add);
    schur_matrix.compress(VectorOperation::add);
  }

  void
  FluidProblem::build_preconditioner()
  {
    TimerOutput::Scope scope(timer, "fluid: preconditioner");
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    amg_data.elliptic              = parameters.model == FluidModel::stokes;
    amg_data.higher_order_elements = true;
    amg_data.smoother_sweeps       = 2;
    amg_data.aggregation_threshold = 0.02;
    std::vector<std::vector<bool>> constant_modes;
    DoFTools::extract_constant_modes(dof_handler,
                                     fe.component_mask(velocities),
                                     constant_modes);
    amg_data.constant_modes = constant_modes;

    velocity_amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    velocity_amg->initialize(system_matrix.block(0, 0), amg_data);
    schur_ilu = std::make_unique<TrilinosWrappers::PreconditionILU>();
    schur_ilu->initialize(schur_matrix.block(1, 1));
  }

  double
  FluidProblem::assemble_residual(const bool with_convection)
  {
    TimerOutput::Scope scope(timer, "fluid: assemble residual");
    residual = 0.;

    const double       rho = parameters.density, mu = parameters.viscosity;
    const QGauss<3>    quadrature(fe.degree + 1);
    FEValues<3>        fe_values(mapping,
                          fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
    const unsigned int n  = fe.n_dofs_per_cell();
    const unsigned int nq = quadrature.size();
    Vector<double>     cell_residual(n);
    std::vector<types::global_dof_index> dof_indices(n);
    std::vector<Tensor<1, 3>>            v(nq), v_old(nq);
    std::vector<Tensor<2, 3>>            grad_v(nq);
    std::vector<double>                  div_v(nq), p(nq);

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current, v);
          fe_values[velocities].get_function_values(previous, v_old);
          fe_values[velocities].get_function_gradients(current, grad_v);
          fe_values[velocities].get_function_divergences(current, div_v);
          fe_values[pressure].get_function_values(current, p);
          cell_residual = 0.;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              Tensor<1, 3> momentum = rho / time_step * (v[q] - v_old[q]);
              if (with_convection)
                momentum += rho * (grad_v[q] * v[q]);
              const double JxW = fe_values.JxW(q);
              for (unsigned int i = 0; i < n; ++i)
                cell_residual(i) +=
                  (momentum * fe_values[velocities].value(i, q) +
                   mu * scalar_product(grad_v[q],
                                       fe_values[velocities].gradient(i, q)) -
                   p[q] * fe_values[velocities].divergence(i, q) -
                   mu * div_v[q] * fe_values[pressure].value(i, q)) *
                  JxW;
            }
          cell->get_dof_indices(dof_indices);
          homogeneous_constraints.distribute_local_to_global(cell_residual,
                                                             dof_indices,
                                                             residual);
        }
    residual.compress(VectorOperation::add);
    residual -= body_force;
    residual -= drive_load;
    if (velocity_load)
      velocity_load(current, residual);
    return residual.l2_norm();
  }

  void
  FluidProblem::set_velocity_load(const VelocityLoad &load)
  {
    velocity_load = load;
  }

  void
  FluidProblem::add_field_load(const TrilinosWrappers::MPI::BlockVector &v,
                               TrilinosWrappers::MPI::BlockVector &result) const
  {
    load_owned = v;
    homogeneous_constraints.distribute(load_owned);
    load_ghosted = load_owned;
    velocity_load(load_ghosted, result);
  }

  namespace
  {
    /// J + L of FluidProblem: the stored matrix and the velocity load.
    template <typename Problem>
    class OperatorWithLoad
    {
    public:
      OperatorWithLoad(const TrilinosWrappers::BlockSparseMatrix &matrix,
                       const Problem                             &problem)
        : matrix(matrix)
        , problem(problem)
      {}

      void
      vmult(TrilinosWrappers::MPI::BlockVector       &dst,
            const TrilinosWrappers::MPI::BlockVector &src) const
      {
        matrix.vmult(dst, src);
        problem(src, dst);
      }

    private:
      const TrilinosWrappers::BlockSparseMatrix &matrix;
      const Problem                             &problem;
    };
  } // namespace

  void
  FluidProblem::assemble_drive_load()
  {
    if (drive.pressure_gradient == 0.)
      return;
    const QGauss<3>                      quadrature(fe.degree + 1);
    FEValues<3>                          fe_values(mapping,
                          fe,
                          quadrature,
                          update_values | update_JxW_values);
    const unsigned int                   n = fe.n_dofs_per_cell();
    Vector<double>                       cell_load(n);
    std::vector<types::global_dof_index> dof_indices(n);
    const FEValuesExtractors::Scalar     axial_velocity(0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_load = 0.;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n; ++i)
              cell_load(i) += drive.pressure_gradient *
                              fe_values[axial_velocity].value(i, q) *
                              fe_values.JxW(q);
          cell->get_dof_indices(dof_indices);
          homogeneous_constraints.distribute_local_to_global(cell_load,
                                                             dof_indices,
                                                             drive_load);
        }
    drive_load.compress(VectorOperation::add);
  }

  std::pair<unsigned int, double>
  FluidProblem::solve_linear_system()
  {
    TimerOutput::Scope         scope(timer, "fluid: solve");
    const StokesPreconditioner preconditioner(system_matrix,
                                              schur_matrix.block(1, 1),
                                              *velocity_amg,
                                              *schur_ilu);
    // The tolerance is relative to the largest residual seen, the scale of
    // the problem, not to this step's: a step that changes little then
    // costs few iterations.
    residual_scale = std::max(residual_scale, residual.l2_norm());
    SolverControl control(parameters.max_linear_iterations,
                          parameters.linear_tolerance * residual_scale);
    SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(
      control,
      SolverFGMRES<TrilinosWrappers::MPI::BlockVector>::AdditionalData(100));
    update = 0.;
    residual *= -1.;
    try
      {
        if (velocity_load)
          {
            const auto load = [this](const auto &v, auto &result) {
              add_field_load(v, result);
            };
            solver.solve(OperatorWithLoad<decltype(load)>(system_matrix, load),
                         update,
                         residual,
                         preconditioner);
          }
        else
          solver.solve(system_matrix, update, residual, preconditioner);
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
    homogeneous_constraints.distribute(update);

    TrilinosWrappers::MPI::BlockVector next(owned, communicator);
    next = current;
    next += update;
    current = next;
    return {control.last_step(), control.last_value()};
  }

  StepReport
  FluidProblem::advance()
  {
    previous = current;
    {
      // Start from the old field with this step's boundary values.
      if (frame_velocity != constrained_frame_velocity)
        {
          make_constraints(boundary_constraints, 1.);
          constrained_frame_velocity = frame_velocity;
        }
      TrilinosWrappers::MPI::BlockVector guess(owned, communicator);
      guess = previous;
      if (velocity_load)
        {
          // The implicit force makes the flow change smoothly from step to
          // step: extrapolate it.
          if (earlier.size() > 0)
            guess.sadd(2., -1., earlier);
          else
            earlier.reinit(owned, communicator);
          earlier = previous;
        }
      boundary_constraints.distribute(guess);
      current = guess;
    }

    const bool navier_stokes = parameters.model == FluidModel::navier_stokes;
    StepReport report;
    const auto check_finite = [&](const double r) {
      if (!std::isfinite(r))
        throw SolverFailure(
          "the fluid residual is not finite: the flow solution has diverged");
      report.residuals.push_back(r);
      return r;
    };

    const double first    = check_finite(assemble_residual(navier_stokes));
    report.final_residual = first;
    if (first <= parameters.linear_tolerance * residual_scale)
      return report;
    if (!navier_stokes)
      {
        // Linear: one solve with the stored operator is exact.
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
        assemble_jacobian(true);
        build_preconditioner();
        const unsigned int iterations = solve_linear_system().first;
        report.linear_iterations += iterations;
        ++report.newton_iterations;
        r                     = check_finite(assemble_residual(true));
        report.final_residual = r;
      }
    return report;
  }

  void
  FluidProblem::set_time_step(const double new_time_step)
  {
    if (new_time_step == time_step)
      return;
    time_step = new_time_step;
    if (parameters.model == FluidModel::stokes)
      {
        assemble_jacobian(false);
        build_preconditioner();
      }
  }

  void
  FluidProblem::set_frame_velocity(const double velocity)
  {
    if (velocity == frame_velocity)
      return;
    if (current.size() > 0)
      {
        TrilinosWrappers::MPI::BlockVector seen_from_new_frame(owned,
                                                               communicator);
        seen_from_new_frame = current;
        seen_from_new_frame.add(frame_velocity - velocity, unit_axial_velocity);
        current = seen_from_new_frame;
      }
    if (earlier.size() > 0)
      earlier.add(frame_velocity - velocity, unit_axial_velocity);
    frame_velocity = velocity;
  }

  double
  FluidProblem::get_frame_velocity() const
  {
    return frame_velocity;
  }

  std::vector<double>
  FluidProblem::gather(const TrilinosWrappers::MPI::BlockVector &v) const
  {
    std::vector<double>     values(dof_handler.n_dofs(), 0.);
    types::global_dof_index offset = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        for (const auto i : owned[b])
          values[offset + i] = v.block(b)(i);
        offset += owned[b].size();
      }
    Utilities::MPI::sum(values, communicator, values);
    return values;
  }

  void
  FluidProblem::scatter(const std::vector<double>          &values,
                        TrilinosWrappers::MPI::BlockVector &v) const
  {
    AssertDimension(values.size(), dof_handler.n_dofs());
    TrilinosWrappers::MPI::BlockVector owned_values(owned, communicator);
    types::global_dof_index            offset = 0;
    for (unsigned int b = 0; b < 2; ++b)
      {
        for (const auto i : owned[b])
          owned_values.block(b)(i) = values[offset + i];
        offset += owned[b].size();
      }
    owned_values.compress(VectorOperation::insert);
    v = owned_values;
  }

  FluidState
  FluidProblem::state() const
  {
    FluidState state;
    state.frame_velocity = frame_velocity;
    state.residual_scale = residual_scale;
    state.solution       = gather(current);
    if (earlier.size() > 0)
      state.earlier_solution = gather(earlier);
    return state;
  }

  void
  FluidProblem::set_state(const FluidState &state)
  {
    scatter(state.solution, current);
    if (!state.earlier_solution.empty())
      {
        earlier.reinit(owned, communicator);
        scatter(state.earlier_solution, earlier);
      }
    frame_velocity = state.frame_velocity;
    residual_scale = state.residual_scale;
  }

  void
  FluidProblem::set_body_force(const TrilinosWrappers::MPI::BlockVector &load)
  {
    body_force = load;
  }

  FlowMeasures
  FluidProblem::measure() const
  {
    TimerOutput::Scope        scope(timer, "fluid: measures");
    const QGauss<3>           quadrature(fe.degree + 1);
    const QGauss<2>           face_quadrature(fe.degree + 1);
    FEValues<3>               fe_values(mapping,
                          fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
    FEFaceValues<3>           face_values(mapping,
                                fe,
                                face_quadrature,
                                update_values | update_normal_vectors |
                                  update_JxW_values);
    std::vector<Tensor<1, 3>> v(quadrature.size()),
      v_face(face_quadrature.size());
    std::vector<double> div_v(quadrature.size()),
      p_face(face_quadrature.size());

    FlowMeasures m;
    double       divergence_squared = 0.;
    // Integrals of p and of 1 over the inlet and the outlet.
    double inlet_pressure = 0., inlet_area = 0., outlet_pressure = 0.,
           outlet_area = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[velocities].get_function_values(current, v);
          fe_values[velocities].get_function_divergences(current, div_v);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              divergence_squared += div_v[q] * div_v[q] * fe_values.JxW(q);
              m.max_velocity = std::max(m.max_velocity, v[q].norm());
            }
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                (cell->face(f)->boundary_id() == FluidBoundary::inlet ||
                 cell->face(f)->boundary_id() == FluidBoundary::outlet))
              {
                const bool outlet =
                  cell->face(f)->boundary_id() == FluidBoundary::outlet;
                face_values.reinit(cell, f);
                face_values[velocities].get_function_values(current, v_face);
                face_values[pressure].get_function_values(current, p_face);
                for (const unsigned int q :
                     face_values.quadrature_point_indices())
                  {
                    const double JxW = face_values.JxW(q);
                    (outlet ? outlet_pressure : inlet_pressure) +=
                      p_face[q] * JxW;
                    (outlet ? outlet_area : inlet_area) += JxW;
                    if (outlet)
                      m.flow_rate +=
                        v_face[q] * face_values.normal_vector(q) * JxW;
                  }
              }
        }
    m.divergence_l2 =
      std::sqrt(Utilities::MPI::sum(divergence_squared, communicator));
    m.max_velocity = Utilities::MPI::max(m.max_velocity, communicator);
    m.flow_rate    = Utilities::MPI::sum(m.flow_rate, communicator);
    // The outlet's normal is e_x: the frame's motion adds V times its area.
    m.lab_flow_rate =
      m.flow_rate +
      frame_velocity * Utilities::MPI::sum(outlet_area, communicator);
    m.pressure_drop = Utilities::MPI::sum(inlet_pressure, communicator) /
                        Utilities::MPI::sum(inlet_area, communicator) -
                      Utilities::MPI::sum(outlet_pressure, communicator) /
                        Utilities::MPI::sum(outlet_area, communicator);
    if (drive.period)
      m.pressure_drop += drive.pressure_gradient * *drive.period;
    return m;
  }

  std::string
  FluidProblem::write_vtu(const std::string &directory,
                          const unsigned int counter,
                          const FieldData   &field_data) const
  {
    TimerOutput::Scope       scope(timer, "fluid: output");
    std::vector<std::string> names(3, "velocity");
    names.emplace_back("pressure");
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(3,
                     DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);

    const LabVelocity lab_velocity(frame_velocity);
    DataOut<3>        data_out;
    data_out.set_flags(fast_vtk_flags());
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(current,
                             names,
                             DataOut<3>::type_dof_data,
                             interpretation);
    data_out.add_data_vector(current, lab_velocity);
    data_out.build_patches(mapping, 2);
    return write_vtu_pieces(
      data_out, directory, "flow", counter, communicator, field_data);
  }

  const TrilinosWrappers::MPI::BlockVector &
  FluidProblem::solution() const
  {
    return current;
  }

  const DoFHandler<3> &
  FluidProblem::get_dof_handler() const
  {
    return dof_handler;
  }

  const MappingQ<3> &
  FluidProblem::get_mapping() const
  {
    return mapping;
  }

  const AffineConstraints<double> &
  FluidProblem::zero_constraints() const
  {
    return homogeneous_constraints;
  }

  const std::vector<IndexSet> &
  FluidProblem::owned_partitioning() const
  {
    return owned;
  }
} // namespace rbc_ifem

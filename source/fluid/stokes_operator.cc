#include <rbc_ifem/fluid/stokes_operator.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/matrix_free/tools.h>

namespace rbc_ifem
{
  StokesOperator::StokesOperator(
    const Mapping<3>                &mapping,
    const DoFHandler<3>             &velocity_dof_handler,
    const DoFHandler<3>             &pressure_dof_handler,
    const AffineConstraints<double> &velocity_constraints,
    const AffineConstraints<double> &pressure_constraints)
    : matrix_free(std::make_shared<MatrixFree<3, double>>())
  {
    typename MatrixFree<3, double>::AdditionalData data;
    // One thread per rank: the ranks use the cores.
    data.tasks_parallel_scheme = MatrixFree<3, double>::AdditionalData::none;
    data.mapping_update_flags =
      update_values | update_gradients | update_JxW_values;
    const std::vector<const DoFHandler<3> *> dof_handlers{
      &velocity_dof_handler, &pressure_dof_handler};
    const std::vector<const AffineConstraints<double> *> constraints{
      &velocity_constraints, &pressure_constraints};
    matrix_free->reinit(mapping, dof_handlers, constraints, QGauss<1>(3), data);
  }

  void
  StokesOperator::set_coefficients(const double new_density,
                                   const double new_viscosity,
                                   const double new_time_step)
  {
    density   = new_density;
    viscosity = new_viscosity;
    time_step = new_time_step;
  }

  void
  StokesOperator::set_convection(const FluidVector &state)
  {
    const unsigned int n_batches = matrix_free->n_cell_batches();
    VelocityEvaluator  velocity(*matrix_free, velocity_index);
    convecting_velocity.reinit(n_batches, velocity.n_q_points);
    convecting_gradient.reinit(n_batches, velocity.n_q_points);
    for (unsigned int cell = 0; cell < n_batches; ++cell)
      {
        velocity.reinit(cell);
        velocity.read_dof_values_plain(state.block(0));
        velocity.evaluate(EvaluationFlags::values | EvaluationFlags::gradients);
        for (const unsigned int q : velocity.quadrature_point_indices())
          {
            convecting_velocity(cell, q) = velocity.get_value(q);
            convecting_gradient(cell, q) = velocity.get_gradient(q);
          }
      }
  }

  void
  StokesOperator::clear_convection()
  {
    convecting_velocity.reinit(0, 0);
    convecting_gradient.reinit(0, 0);
  }

  void
  StokesOperator::initialize_dof_vector(FluidVector &v) const
  {
    v.reinit(2);
    matrix_free->initialize_dof_vector(v.block(0), velocity_index);
    matrix_free->initialize_dof_vector(v.block(1), pressure_index);
    v.collect_sizes();
  }

  void
  StokesOperator::apply_on_cells(
    const MatrixFree<3, double>                 &data,
    FluidVector                                 &dst,
    const FluidVector                           &src,
    const std::pair<unsigned int, unsigned int> &cells) const
  {
    VelocityEvaluator velocity(data, velocity_index);
    PressureEvaluator pressure(data, pressure_index);
    const double      mass_factor = density / time_step;
    const bool        convection  = convecting_velocity.size(0) > 0;
    for (unsigned int cell = cells.first; cell < cells.second; ++cell)
      {
        velocity.reinit(cell);
        pressure.reinit(cell);
        velocity.gather_evaluate(src.block(0),
                                 EvaluationFlags::values |
                                   EvaluationFlags::gradients);
        pressure.gather_evaluate(src.block(1), EvaluationFlags::values);
        for (const unsigned int q : velocity.quadrature_point_indices())
          {
            const Tensor<1, 3, VectorizedArray<double>> v =
              velocity.get_value(q);
            Tensor<2, 3, VectorizedArray<double>> grad_v =
              velocity.get_gradient(q);
            const VectorizedArray<double>         divergence = trace(grad_v);
            Tensor<1, 3, VectorizedArray<double>> value      = mass_factor * v;
            if (convection)
              value += density * (grad_v * convecting_velocity(cell, q) +
                                  convecting_gradient(cell, q) * v);
            grad_v *= viscosity;
            const VectorizedArray<double> p = pressure.get_value(q);
            for (unsigned int d = 0; d < 3; ++d)
              grad_v[d][d] -= p;
            velocity.submit_value(value, q);
            velocity.submit_gradient(grad_v, q);
            pressure.submit_value(-viscosity * divergence, q);
          }
        velocity.integrate_scatter(EvaluationFlags::values |
                                     EvaluationFlags::gradients,
                                   dst.block(0));
        pressure.integrate_scatter(EvaluationFlags::values, dst.block(1));
      }
  }

  void
  StokesOperator::vmult(FluidVector &dst, const FluidVector &src) const
  {
    matrix_free->cell_loop(
      &StokesOperator::apply_on_cells, this, dst, src, /*zero_dst=*/true);
    for (unsigned int b = 0; b < 2; ++b)
      for (const unsigned int i : matrix_free->get_constrained_dofs(b))
        dst.block(b).local_element(i) = src.block(b).local_element(i);
  }

  void
  StokesOperator::residual(FluidVector          &dst,
                           const FluidVector    &state,
                           const VelocityVector &old_velocity,
                           const bool            convection) const
  {
    const double mass_factor = density / time_step;
    const auto   on_cells =
      [&](const MatrixFree<3, double> &data,
          FluidVector                 &result,
          const FluidVector &,
          const std::pair<unsigned int, unsigned int> &cells) {
        VelocityEvaluator velocity(data, velocity_index);
        VelocityEvaluator old(data, velocity_index);
        PressureEvaluator pressure(data, pressure_index);
        for (unsigned int cell = cells.first; cell < cells.second; ++cell)
          {
            velocity.reinit(cell);
            old.reinit(cell);
            pressure.reinit(cell);
            // Plain: the fields hold their boundary values, which the
            // homogeneous constraints of the MatrixFree would drop.
            velocity.read_dof_values_plain(state.block(0));
            velocity.evaluate(EvaluationFlags::values |
                              EvaluationFlags::gradients);
            old.read_dof_values_plain(old_velocity);
            old.evaluate(EvaluationFlags::values);
            pressure.read_dof_values_plain(state.block(1));
            pressure.evaluate(EvaluationFlags::values);
            for (const unsigned int q : velocity.quadrature_point_indices())
              {
                const Tensor<1, 3, VectorizedArray<double>> v =
                  velocity.get_value(q);
                Tensor<2, 3, VectorizedArray<double>> grad_v =
                  velocity.get_gradient(q);
                const VectorizedArray<double> divergence = trace(grad_v);
                Tensor<1, 3, VectorizedArray<double>> value =
                  mass_factor * (v - old.get_value(q));
                if (convection)
                  value += density * (grad_v * v);
                grad_v *= viscosity;
                const VectorizedArray<double> p = pressure.get_value(q);
                for (unsigned int d = 0; d < 3; ++d)
                  grad_v[d][d] -= p;
                velocity.submit_value(value, q);
                velocity.submit_gradient(grad_v, q);
                pressure.submit_value(-viscosity * divergence, q);
              }
            velocity.integrate_scatter(EvaluationFlags::values |
                                         EvaluationFlags::gradients,
                                       result.block(0));
            pressure.integrate_scatter(EvaluationFlags::values,
                                       result.block(1));
          }
      };
    matrix_free->cell_loop<FluidVector, FluidVector>(on_cells,
                                                     dst,
                                                     state,
                                                     /*zero_dst=*/true);
  }

  void
  StokesOperator::pressure_gradient_on_cells(
    const MatrixFree<3, double>                 &data,
    VelocityVector                              &dst,
    const PressureVector                        &src,
    const std::pair<unsigned int, unsigned int> &cells) const
  {
    VelocityEvaluator velocity(data, velocity_index);
    PressureEvaluator pressure(data, pressure_index);
    for (unsigned int cell = cells.first; cell < cells.second; ++cell)
      {
        velocity.reinit(cell);
        pressure.reinit(cell);
        pressure.gather_evaluate(src, EvaluationFlags::values);
        for (const unsigned int q : velocity.quadrature_point_indices())
          {
            Tensor<2, 3, VectorizedArray<double>> flux;
            for (unsigned int d = 0; d < 3; ++d)
              flux[d][d] = -pressure.get_value(q);
            velocity.submit_gradient(flux, q);
          }
        velocity.integrate_scatter(EvaluationFlags::gradients, dst);
      }
  }

  void
  StokesOperator::apply_pressure_gradient(VelocityVector       &dst,
                                          const PressureVector &pressure) const
  {
    matrix_free->cell_loop(&StokesOperator::pressure_gradient_on_cells,
                           this,
                           dst,
                           pressure,
                           /*zero_dst=*/true);
  }

  void
  StokesOperator::pressure_mass_on_cell(PressureEvaluator &phi) const
  {
    phi.evaluate(EvaluationFlags::values);
    for (const unsigned int q : phi.quadrature_point_indices())
      phi.submit_value(phi.get_value(q), q);
    phi.integrate(EvaluationFlags::values);
  }

  std::shared_ptr<DiagonalMatrix<PressureVector>>
  StokesOperator::inverse_pressure_mass_diagonal() const
  {
    auto inverse = std::make_shared<DiagonalMatrix<PressureVector>>();
    PressureVector &diagonal = inverse->get_vector();
    matrix_free->initialize_dof_vector(diagonal, pressure_index);
    MatrixFreeTools::compute_diagonal(*matrix_free,
                                      diagonal,
                                      &StokesOperator::pressure_mass_on_cell,
                                      this,
                                      pressure_index);
    for (const unsigned int i :
         matrix_free->get_constrained_dofs(pressure_index))
      diagonal.local_element(i) = 1.;
    for (double &d : diagonal)
      d = 1. / d;
    return inverse;
  }

  void
  StokesOperator::add_uniform_force(const Tensor<1, 3> &f,
                                    VelocityVector     &load) const
  {
    const Tensor<1, 3, VectorizedArray<double>> force(f);
    VelocityEvaluator velocity(*matrix_free, velocity_index);
    for (unsigned int cell = 0; cell < matrix_free->n_cell_batches(); ++cell)
      {
        velocity.reinit(cell);
        for (const unsigned int q : velocity.quadrature_point_indices())
          velocity.submit_value(force, q);
        velocity.integrate_scatter(EvaluationFlags::values, load);
      }
    load.compress(VectorOperation::add);
  }

  std::shared_ptr<const MatrixFree<3, double>>
  StokesOperator::get_matrix_free() const
  {
    return matrix_free;
  }
} // namespace rbc_ifem

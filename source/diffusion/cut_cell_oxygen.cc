#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/bdf2.h>
#include <rbc_ifem/diffusion/cut_cell_oxygen.h>
#include <rbc_ifem/diffusion/scaled_amg_solve.h>
#include <rbc_ifem/diffusion/side_field.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rbc_ifem
{
  CutCellOxygen::CutCellOxygen(const CutCellGeometry     &geometry,
                               const DiffusionParameters &parameters,
                               const OxygenParameters    &oxygen,
                               const OxygenBinding       &binding,
                               const types::boundary_id   pressure_boundary,
                               TimerOutput               &timer)
    : CutCellProblem(
        geometry,
        [&] {
          // P = P_A on the alveolar surface: the base's constraints.
          DiffusionParameters d = parameters;
          d.alveolar_pressure   = oxygen.alveolar_pressure;
          return d;
        }(),
        [oxygen](const unsigned int id) { return oxygen.permeability(id); },
        pressure_boundary,
        timer)
    , oxygen(oxygen)
    , binding(binding)
    , n_colours(geometry.n_colours())
  {
    if (n_colours == 0)
      throw std::logic_error("CutCellOxygen needs a CutCellGeometry that "
                             "separates the cells' insides.");
    // Each output field is the component of the side the mesh cell is on.
    const auto component = [this](const unsigned int which) {
      return [this, which](const DoFHandler<3>::cell_iterator &cell) {
        const std::vector<unsigned int> fields = fields_on(cell);
        if (which == 0)
          return fields.front() == 0 ? 0u : numbers::invalid_unsigned_int;
        if (fields.back() == 0)
          return numbers::invalid_unsigned_int;
        return which == 1 ? fields.back() - n_colours : fields.back();
      };
    };
    output_fields.push_back(std::make_unique<SideField>("po2", component(0)));
    output_fields.push_back(
      std::make_unique<SideField>("po2_cell", component(1)));
    output_fields.push_back(
      std::make_unique<SideField>("saturation", component(2)));
    set_up_system(FESystem<3>(FE_Q<3>(parameters.degree), 1 + 2 * n_colours));
  }

  std::vector<unsigned int>
  CutCellOxygen::fields_on(const Triangulation<3>::cell_iterator &cell) const
  {
    std::vector<unsigned int> fields = pressure_fields_on(cell);
    if (fields.back() > 0)
      fields.push_back(fields.back() + n_colours);
    return fields;
  }

  std::vector<unsigned int>
  CutCellOxygen::pressure_fields_on(
    const Triangulation<3>::cell_iterator &cell) const
  {
    return plasma_and_cell_fields(cell);
  }

  NonMatching::RegionUpdateFlags
  CutCellOxygen::assembly_flags() const
  {
    NonMatching::RegionUpdateFlags flags;
    flags.inside = update_gradients | update_JxW_values;
    // (add_cytoplasm_reaction() reads the values, at rate zero.)
    flags.outside = update_values | update_gradients | update_JxW_values;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    return flags;
  }

  void
  CutCellOxygen::add_cell_terms(const NonMatching::FEValues<3> &values,
                                const DoFHandler<3>::active_cell_iterator &cell,
                                const CutCellShapes &shapes,
                                FullMatrix<double>  &matrix) const
  {
    if (const auto &plasma = values.get_inside_fe_values())
      add_plasma_diffusion(*plasma,
                           permeability(cell->material_id()),
                           shapes,
                           matrix);
    if (const auto &cytoplasm = values.get_outside_fe_values())
      {
        add_cytoplasm_reaction(
          *cytoplasm, field_permeability(1, cell), 0., shapes, matrix);
        // S diffuses on the same part of the cell, in its own rows.
        const FiniteElement<3> &fe         = cell->get_fe();
        const unsigned int      saturation = fields_on(cell).back();
        CutCellShapes           hemoglobin;
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          hemoglobin.side.push_back(
            fe.system_to_component_index(i).first == saturation ? 1 : -1);
        hemoglobin.jump_sign.assign(fe.n_dofs_per_cell(), 0.);
        add_cytoplasm_reaction(*cytoplasm,
                               field_permeability(saturation, cell),
                               0.,
                               hemoglobin,
                               matrix);
      }
    if (const auto &membrane = values.get_surface_fe_values())
      add_membrane_coupling(*membrane, membrane_coupling(cell), shapes, matrix);
  }

  MembraneCoupling
  CutCellOxygen::membrane_coupling(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    // Hansbo's weights: the flux from the side with the larger αD.
    const double gamma  = nitsche_weight(cell);
    const double plasma = permeability(cell->material_id());
    const double inside = field_permeability(1, cell);
    const double w0 = inside / (plasma + inside), w1 = 1. - w0;
    return {w0 * plasma,
            w1 * inside,
            2. * gamma * (w0 * w0 * plasma + w1 * w1 * inside)};
  }

  double
  CutCellOxygen::field_permeability(
    const unsigned int                         field,
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    if (field == 0)
      return CutCellProblem::field_permeability(field, cell);
    if (field <= n_colours)
      return oxygen.cytoplasm_solubility * oxygen.cytoplasm_diffusivity;
    return oxygen.heme_capacity * oxygen.hemoglobin_diffusivity;
  }

  std::string
  CutCellOxygen::flux_name() const
  {
    return "o2_flux";
  }

  void
  CutCellOxygen::add_pressure_fields(DataOut<3> &data_out) const
  {
    for (const auto &field : output_fields)
      data_out.add_data_vector(solution, *field);
  }

  Vector<double>
  CutCellOxygen::lumped_capacities(
    const NonMatching::FEValues<3>            &values,
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    const FiniteElement<3> &fe = cell->get_fe();
    Vector<double>          capacities(fe.n_dofs_per_cell());
    // HRZ on each part: the diagonal of the part's mass matrix, scaled so
    // that each field's entries sum to the part's volume.
    const auto lump = [&](const FEValues<3>               &part,
                          const std::vector<unsigned int> &fields,
                          const std::vector<double>       &coefficients) {
      double volume = 0.;
      for (const unsigned int q : part.quadrature_point_indices())
        volume += part.JxW(q);
      for (unsigned int f = 0; f < fields.size(); ++f)
        {
          Vector<double> diagonal(fe.n_dofs_per_cell());
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            if (fe.system_to_component_index(i).first == fields[f])
              for (const unsigned int q : part.quadrature_point_indices())
                diagonal[i] +=
                  std::pow(part.shape_value(i, q), 2) * part.JxW(q);
          const double sum = diagonal.l1_norm();
          if (sum > 0.)
            capacities.add(coefficients[f] * volume / sum, diagonal);
        }
    };
    const std::vector<unsigned int> fields = fields_on(cell);
    if (const auto &plasma = values.get_inside_fe_values())
      lump(*plasma, {0}, {oxygen.solubility(cell->material_id())});
    if (const auto &cytoplasm = values.get_outside_fe_values())
      lump(*cytoplasm,
           {fields.end()[-2], fields.back()},
           {oxygen.cytoplasm_solubility, oxygen.heme_capacity});
    return capacities;
  }

  void
  CutCellOxygen::assemble()
  {
    assemble_operator();
    step_sigma_over_dt = 0.; // step_matrix is set up anew
    TimerOutput::Scope scope(timer, "oxygen: capacities");
    capacity.reinit(owned_dofs, communicator);
    NonMatching::RegionUpdateFlags flags;
    flags.inside  = update_values | update_JxW_values;
    flags.outside = update_values | update_JxW_values;
    std::vector<types::global_dof_index> dofs;
    for_each_field_cell(flags, [&](const auto &values, const auto &cell) {
      dofs.resize(cell->get_fe().n_dofs_per_cell());
      cell->get_dof_indices(dofs);
      add_to_free_dofs(lumped_capacities(values, cell), dofs, capacity);
    });
    capacity.compress(VectorOperation::add);
    find_binding_pairs();
    // The DoFs held at P_A, whose rows give the inflow at every step.
    std::vector<bool> pressure_only(1 + 2 * n_colours, false);
    pressure_only[0] = true;
    held_dofs        = DoFTools::extract_boundary_dofs(dof_handler,
                                                ComponentMask(pressure_only),
                                                {pressure_boundary});
  }

  void
  CutCellOxygen::add_to_free_dofs(
    const Vector<double>                       &local,
    const std::vector<types::global_dof_index> &dofs,
    TrilinosWrappers::MPI::Vector              &global) const
  {
    // A hanging node's weights on Q2 include −1/8: distributed through the
    // constraints as they are, a capacity can come out negative (it did, at
    // 16 of 68,599 DoFs, and P's diagonal with it). Each constrained
    // node's capacity goes to the nodes it hangs on by the weights' sizes
    // instead, |c_j| / Σ|c_j|, which keeps the total; a node held at a
    // value (P_A, or zero outside its field) has none.
    for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        const auto *line = constraints.get_constraint_entries(dofs[i]);
        if (!constraints.is_constrained(dofs[i]))
          global[dofs[i]] += local[i];
        else if (line != nullptr && !line->empty())
          {
            double sum = 0.;
            for (const auto &[dof, weight] : *line)
              sum += std::abs(weight);
            for (const auto &[dof, weight] : *line)
              global[dof] += local[i] * std::abs(weight) / sum;
          }
      }
  }

  void
  CutCellOxygen::find_binding_pairs()
  {
    binding_nodes.clear();
    std::vector<types::global_dof_index> dofs;
    for (const auto &cell : dof_handler.active_cell_iterators())
      // A DoF this rank owns can lie on its ghost cells only.
      if (!cell->is_artificial() && fields_on(cell).back() > n_colours)
        {
          const FiniteElement<3> &fe         = cell->get_fe();
          const unsigned int      saturation = fields_on(cell).back();
          dofs.resize(fe.n_dofs_per_cell());
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (fe.system_to_component_index(i).first == saturation &&
                owned_dofs.is_element(dofs[i]) &&
                !constraints.is_constrained(dofs[i]))
              {
                const unsigned int node =
                  fe.system_to_component_index(i).second;
                const unsigned int pressure =
                  fe.component_to_system_index(saturation - n_colours, node);
                // deal.II gives all components at a node one owner.
                Assert(owned_dofs.is_element(dofs[pressure]),
                       ExcInternalError());
                binding_nodes.push_back(
                  {dofs[pressure], dofs[i], geometry.inside_of(cell), {}});
              }
        }
    const auto dof = [](const BindingNode &node) { return node.saturation; };
    std::sort(binding_nodes.begin(),
              binding_nodes.end(),
              [&](const auto &a, const auto &b) { return dof(a) < dof(b); });
    binding_nodes.erase(std::unique(binding_nodes.begin(),
                                    binding_nodes.end(),
                                    [&](const auto &a, const auto &b) {
                                      return dof(a) == dof(b);
                                    }),
                        binding_nodes.end());
  }

  void
  CutCellOxygen::start(const double pressure)
  {
    TrilinosWrappers::MPI::Vector u(owned_dofs, communicator);
    const double saturation = binding.equilibrium_saturation(pressure);
    std::vector<types::global_dof_index> dofs;
    for (const auto &cell : dof_handler.active_cell_iterators())
      // A DoF this rank owns can lie on its ghost cells only.
      if (!cell->is_artificial() && !fields_on(cell).empty())
        {
          const FiniteElement<3> &fe = cell->get_fe();
          dofs.resize(fe.n_dofs_per_cell());
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned_dofs.is_element(dofs[i]))
              u[dofs[i]] = fe.system_to_component_index(i).first > n_colours ?
                             saturation :
                             pressure;
        }
    u.compress(VectorOperation::insert);
    constraints.distribute(u);
    fields = older_fields = oldest_fields = u;
    solution                              = u;
    current_time                          = 0.;
    n_steps                               = 0;
    wall = old_wall = 0.;
    set_free_dofs();
  }

  void
  CutCellOxygen::set_free_dofs()
  {
    free_dofs.reinit(capacity);
    error_weights.reinit(capacity);
    for (const auto i : owned_dofs)
      if (!constraints.is_constrained(i))
        {
          free_dofs[i]     = 1.;
          error_weights[i] = 1. / oxygen.alveolar_pressure;
        }
    for (const BindingNode &node : binding_nodes)
      error_weights[node.saturation] = 1.;
    free_dofs.compress(VectorOperation::insert);
    error_weights.compress(VectorOperation::insert);
    step_sigma_over_dt = 0.; // conserve() needs free_row_sum anew
  }

  void
  CutCellOxygen::solve()
  {
    throw std::logic_error("CutCellOxygen is solved in time: advance().");
  }

  void
  CutCellOxygen::advance(const double time_step)
  {
    try_step(time_step);
    accept_step();
  }

  double
  CutCellOxygen::try_step(const double time_step)
  {
    TimerOutput::Scope scope(timer, "oxygen: time step");
    // BDF2 with the last step's length (BDF1 for the first step).
    const Bdf2                    bdf(time_step, n_steps == 0 ? 0. : last_step);
    TrilinosWrappers::MPI::Vector history(fields), start(fields);
    history.sadd(bdf.now, -bdf.before, older_fields);
    history.scale(capacity);
    history /= time_step;
    start.sadd(1. + bdf.growth, -bdf.growth, older_fields);
    try
      {
        solve_step(bdf.sigma / time_step, history, start);
      }
    catch (const SolverFailure &)
      {
        // The step matrix holds the failed iterate's binding, perhaps not
        // finite: built anew for the next try, whatever its σ/Δt.
        step_sigma_over_dt = 0.;
        throw;
      }

    // The wall's O2 by the same rule, so that it and the amounts change
    // alike: (σ Wⁿ⁺¹ − the history of W)/Δt = the inflow.
    next_wall =
      (time_step * alveolar_inflow() + bdf.now * wall - bdf.before * old_wall) /
      bdf.sigma;
    next_step = time_step;
    return n_steps >= 2 && bdf.growth > 0. ? local_error(time_step) : 0.;
  }

  void
  CutCellOxygen::accept_step()
  {
    old_wall      = wall;
    wall          = next_wall;
    oldest_fields = older_fields;
    older_fields  = fields;
    fields        = solution;
    current_time += next_step;
    older_step = last_step;
    last_step  = next_step;
    ++n_steps;
  }

  double
  CutCellOxygen::local_error(const double time_step) const
  {
    // Bdf2Error's estimate at every free DoF, P relative to P_A and S as
    // it is; their root mean square.
    const Bdf2Error               estimate(time_step, last_step, older_step);
    TrilinosWrappers::MPI::Vector error(fields);
    error = solution;
    error.add(-estimate.current, fields, -estimate.last, older_fields);
    error.add(-estimate.before_last, oldest_fields);
    error.scale(error_weights);
    return estimate.factor * error.l2_norm() /
           std::sqrt(std::max(free_dofs.l1_norm(), 1.));
  }

  void
  CutCellOxygen::set_up_step_matrix(const double sigma_over_dt)
  {
    TimerOutput::Scope scope(timer, "oxygen: step matrix");
    // matrix's graph and values, without its buffer for other ranks' rows:
    // nothing is added to those here.
    step_matrix.reinit(matrix.trilinos_matrix(), true);
    for (const auto i : owned_dofs)
      if (capacity[i] > 0.)
        step_matrix.add(i, i, sigma_over_dt * capacity[i]);
    step_matrix.compress(VectorOperation::add);
    for (BindingNode &node : binding_nodes)
      node.binding = {};
    step_sigma_over_dt = sigma_over_dt;

    // 1ᵀ A 1 over the free rows and columns. The binding adds nothing to
    // it (what leaves P₁'s row enters S's), so it holds for every Newton
    // iteration of every step with this σ/Δt.
    TrilinosWrappers::MPI::Vector row_sums(free_dofs);
    step_matrix.vmult(row_sums, free_dofs);
    free_row_sum = row_sums * free_dofs;
  }

  void
  CutCellOxygen::conserve(const TrilinosWrappers::MPI::Vector &residual,
                          TrilinosWrappers::MPI::Vector       &u) const
  {
    // The O2 balance of the step misses by Σ residual (each row is the
    // O2 balance of its node; the binding's rows sum to zero). Shifting
    // the free DoFs by β = Σ residual / 1ᵀ A 1 makes that sum zero: it is
    // linear in u, the binding drops out of it.
    const double beta = (residual * free_dofs) / free_row_sum;
    u.add(beta, free_dofs);
    constraints.distribute(u);
  }

  double
  CutCellOxygen::scaled_norm(const TrilinosWrappers::MPI::Vector &v) const
  {
    // |D v|, D = diag(A)^-1/2: the norm GMRES's tolerance is set in.
    double sum = 0.;
    for (const auto i : owned_dofs)
      sum += v[i] * v[i] / step_matrix.diag_element(i);
    return std::sqrt(Utilities::MPI::sum(sum, communicator));
  }

  void
  CutCellOxygen::solve_step(const double                         sigma_over_dt,
                            const TrilinosWrappers::MPI::Vector &history,
                            const TrilinosWrappers::MPI::Vector &start)
  {
    if (sigma_over_dt != step_sigma_over_dt)
      set_up_step_matrix(sigma_over_dt);
    TrilinosWrappers::MPI::Vector u(start);
    newton_iterations = 0;
    linear_iterations = 0;
    double first_norm = 0.;
    for (;;)
      {
        TrilinosWrappers::MPI::Vector b(rhs);
        b += history;
        {
          TimerOutput::Scope scope(timer, "oxygen: binding");
          set_binding(u, b);
        }
        // Converged when the residual at u, F(u) = b − A(u) u with the
        // binding linearised at u, is within Newton's tolerance of the
        // step's first, at the start, after at least one solve. (Not of b:
        // b holds c uⁿ/Δt, which dwarfs what moves in a step. Nor may the
        // start pass unsolved: near equilibrium the extrapolation's residual
        // is tiny but not zero, and accepted extrapolations drifted past
        // P_A, by 0.1 Torr in a few 5 ms steps with the test relative to b,
        // by 0.004 Torr with a floor of 1e-3 |D b| under the first residual
        // at GMRES tolerance 1e-6. Not on the change of u: a node of a
        // sliver of a cut cell, with a diagonal 1e9 times below the others',
        // drifted by 5e-5 of P_A per iteration while the residual stayed
        // put.) Each GMRES solve takes the residual down by its tolerance
        // (an inexact Newton method), but not below round-off; the factor
        // 10 leaves room for GMRES's preconditioned residual, which it
        // meets, and for the linearisation.
        TrilinosWrappers::MPI::Vector x(u), residual(b);
        // The constrained rows say x = 0 (distribute() sets their values).
        constraints.set_zero(x);
        step_matrix.vmult(residual, x);
        residual.sadd(-1., b);
        const double norm = scaled_norm(residual);
        if (!std::isfinite(norm))
          throw SolverFailure("O2 transport: the fields are not finite.");
        const double bnorm     = scaled_norm(b);
        const double reachable = round_off * bnorm;
        if (newton_iterations == 0)
          first_norm = norm;
        else if (norm <= newton_tolerance *
                           std::max(parameters.linear_tolerance * first_norm,
                                    reachable))
          {
            conserve(residual, u);
            break;
          }
        if (newton_iterations == max_newton_iterations)
          throw SolverFailure(
            "O2 transport: Newton's method did not converge in " +
            std::to_string(max_newton_iterations) +
            " iterations. Shorten Transit/Time step.");
        if (newton_iterations == 0)
          {
            TimerOutput::Scope scope(timer, "oxygen: preconditioner");
            preconditioner.initialize(step_matrix,
                                      binding_pairs(),
                                      parameters.degree);
          }
        linear_iterations +=
          solve_linear(b,
                       x,
                       std::max(parameters.linear_tolerance * norm, reachable) /
                         bnorm);
        u = x;
        ++newton_iterations;
      }
    solution = u;
  }

  unsigned int
  CutCellOxygen::solve_linear(const TrilinosWrappers::MPI::Vector &b,
                              TrilinosWrappers::MPI::Vector       &u,
                              const double                         tolerance)
  {
    TimerOutput::Scope scope(timer, "oxygen: GMRES");
    SolverControl      control(parameters.max_linear_iterations, tolerance);
    try
      {
        SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
          control,
          SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(50));
        solve_scaled(
          gmres, step_matrix, preconditioner, owned_dofs, b, u, control);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw no_convergence("O2 transport (cut cells): GMRES",
                             e,
                             control.tolerance(),
                             "Raise Diffusion/Max linear iterations, or "
                             "shorten Transit/Time step.");
      }
    constraints.distribute(u);
    return control.last_step();
  }

  std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
  CutCellOxygen::binding_pairs() const
  {
    std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
      pairs;
    for (const BindingNode &node : binding_nodes)
      pairs.emplace_back(node.pressure, node.saturation);
    return pairs;
  }

  void
  CutCellOxygen::set_binding(const TrilinosWrappers::MPI::Vector &u,
                             TrilinosWrappers::MPI::Vector       &b)
  {
    // Per node, with w = C × the lumped volume (S's capacity): the binding
    // w q leaves P₁'s row and enters S's, linearised at u:
    // q ≈ q₀ + q_P P + q_S S. An iterate with S > 1 (the extrapolated
    // start overshoots where S rose fast) has q_P < 0, which can make P₁'s
    // diagonal negative: the Jacobian takes q_P ≥ 0 there, which changes
    // Newton's path, not where it ends. Only these four entries per node
    // change between iterations: step_matrix gets the differences.
    for (BindingNode &node : binding_nodes)
      {
        const auto        p = node.pressure, s = node.saturation;
        const double      w        = capacity[s];
        const BindingRate rate     = binding.rate(u[p], u[s]);
        const double      dq_dP    = std::max(rate.dq_dP, 0.);
        const double      constant = rate.q - dq_dP * u[p] - rate.dq_dS * u[s];
        b[p] -= w * constant;
        b[s] += w * constant;
        const std::array<double, 4> jacobian = {
          {w * dq_dP, w * rate.dq_dS, -w * dq_dP, -w * rate.dq_dS}};
        const types::global_dof_index rows[4]    = {p, p, s, s},
                                      columns[4] = {p, s, p, s};
        for (unsigned int k = 0; k < 4; ++k)
          step_matrix.add(rows[k], columns[k], jacobian[k] - node.binding[k]);
        node.binding = jacobian;
      }
    step_matrix.compress(VectorOperation::add);
    b.compress(VectorOperation::add);
  }

  double
  CutCellOxygen::alveolar_inflow() const
  {
    // The rows held at P_A, unconstrained: Σ (K u) over their DoFs is what
    // flows in there (their capacity times ∂P/∂t is zero).
    const IndexSet                      &held = held_dofs;
    const FiniteElement<3>              &fe   = dof_handler.get_fe(0);
    FEValues<3>                          values(geometry.mapping(),
                       fe,
                       QGauss<3>(parameters.degree + 1),
                       update_gradients | update_JxW_values);
    const FEValuesExtractors::Scalar     pressure(0);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    Vector<double>                       local(fe.n_dofs_per_cell());
    std::vector<Tensor<1, 3>>            gradients(values.n_quadrature_points);
    double                               inflow = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && cell->at_boundary() &&
          cell->active_fe_index() == 0)
        {
          cell->get_dof_indices(dofs);
          if (std::none_of(dofs.begin(), dofs.end(), [&](const auto dof) {
                return held.is_element(dof);
              }))
            continue;
          // Its rows are those of the plasma's diffusion on a whole cell:
          // the alveolar surface is far from every membrane, so no cell
          // there is cut or has a ghost penalty.
          AssertThrow(!geometry.is_cut(cell),
                      ExcMessage("A cut cell touches the alveolar surface."));
          values.reinit(cell);
          values[pressure].get_function_gradients(solution, gradients);
          const double kappa = permeability(cell->material_id());
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (held.is_element(dofs[i]) &&
                fe.system_to_component_index(i).first == 0)
              for (const unsigned int q : values.quadrature_point_indices())
                inflow += kappa *
                          (gradients[q] * values[pressure].gradient(i, q)) *
                          values.JxW(q);
        }
    return Utilities::MPI::sum(inflow, communicator);
  }

  double
  CutCellOxygen::time() const
  {
    return current_time;
  }

  std::vector<CutCellOxygen::CellState>
  CutCellOxygen::cell_states() const
  {
    // Per cell: volume, O2, ∫ S and ∫ P, summed over the ranks at once.
    const unsigned int  n = geometry.membranes().size();
    std::vector<double> sums(4 * n, 0.);
    for (const BindingNode &node : binding_nodes)
      {
        const double volume = capacity[node.saturation] / oxygen.heme_capacity;
        const double P = fields[node.pressure], S = fields[node.saturation];
        sums[4 * node.cell] += volume;
        sums[4 * node.cell + 1] +=
          capacity[node.pressure] * P + capacity[node.saturation] * S;
        sums[4 * node.cell + 2] += volume * S;
        sums[4 * node.cell + 3] += volume * P;
      }
    Utilities::MPI::sum(sums, communicator, sums);
    std::vector<CellState> states(n);
    // Every cell has nodes in the mesh that resolves it; the guard keeps a
    // degenerate one from writing NaN.
    for (unsigned int c = 0; c < n; ++c)
      {
        const double volume = std::max(sums[4 * c], 1e-300);
        states[c]           = {sums[4 * c],
                               sums[4 * c + 1],
                               sums[4 * c + 2] / volume,
                               sums[4 * c + 3] / volume};
      }
    return states;
  }

  CutCellOxygen::Amounts
  CutCellOxygen::amounts() const
  {
    TrilinosWrappers::MPI::Vector o2(capacity);
    o2.scale(fields);
    double bound = 0.;
    for (const BindingNode &node : binding_nodes)
      bound += o2[node.saturation];
    bound        = Utilities::MPI::sum(bound, communicator);
    double total = 0.;
    for (const auto i : owned_dofs)
      total += o2[i];
    total = Utilities::MPI::sum(total, communicator);
    return {total - bound, bound};
  }

  double
  CutCellOxygen::wall_oxygen() const
  {
    return wall;
  }

  std::pair<unsigned int, unsigned int>
  CutCellOxygen::last_iterations() const
  {
    return {newton_iterations, linear_iterations};
  }

  void
  CutCellOxygen::update_flux_map()
  {
    compute_flows();
  }
} // namespace rbc_ifem

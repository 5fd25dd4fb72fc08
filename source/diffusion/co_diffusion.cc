#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/diffusion/diagonally_scaled.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  /**
   * Where the membranes' quadrature points sit in the volume mesh. Point k
   * of membrane cell c is quadrature point k % n_q of that cell; each entry
   * of @p points says which volume cell holds it and where in that cell's
   * reference coordinates. Entries are sorted by membrane cell, then by
   * volume cell, so a (membrane cell, volume cell) pair is one run.
   */
  struct CODiffusion::CouplingData
  {
    struct Point
    {
      unsigned int                                 membrane_cell;
      unsigned int                                 q;
      typename DoFHandler<3>::active_cell_iterator volume_cell;
      dealii::Point<3>                             reference;
    };

    /**
     * Call @p f(membrane cell, volume cell, first, last) for every run of
     * points [first, last) shared by one membrane cell and one volume cell.
     */
    template <typename Function>
    void
    for_each_run(const Function &f) const
    {
      for (auto first = points.begin(); first != points.end();)
        {
          auto last = first;
          while (last != points.end() &&
                 last->membrane_cell == first->membrane_cell &&
                 last->volume_cell == first->volume_cell)
            ++last;
          f(first->membrane_cell, first->volume_cell, first, last);
          first = last;
        }
    }

    QGauss<2>                        quadrature{3};
    std::vector<Point>               points;
    std::vector<std::vector<double>> JxW; ///< [membrane cell][q]
    std::vector<std::vector<types::global_dof_index>> multiplier_dofs;
  };

  namespace
  {
    /**
     * The saddle point operator [A_γ Bᵀ; B 0] on (P, λ), applied without
     * assembling it: B is stored once, Bᵀ is its transpose product.
     */
    class SaddlePointOperator
    {
    public:
      SaddlePointOperator(const TrilinosWrappers::SparseMatrix &A,
                          const TrilinosWrappers::SparseMatrix &B)
        : A(A)
        , B(B)
      {}

      void
      vmult(TrilinosWrappers::MPI::BlockVector       &dst,
            const TrilinosWrappers::MPI::BlockVector &src) const
      {
        A.vmult(dst.block(0), src.block(0));
        B.Tvmult_add(dst.block(0), src.block(1));
        B.vmult(dst.block(1), src.block(0));
      }

    private:
      const TrilinosWrappers::SparseMatrix &A;
      const TrilinosWrappers::SparseMatrix &B;
    };

    /**
     * The augmented-Lagrangian block upper-triangular preconditioner:
     * λ ← -γ W r_λ (the Schur complement of the augmented system is
     * (S⁻¹ + γW)⁻¹ ≈ (γW)⁻¹), then P ← AMG(r_P - Bᵀ λ).
     */
    class AugmentedLagrangianPreconditioner
    {
    public:
      AugmentedLagrangianPreconditioner(
        const TrilinosWrappers::SparseMatrix    &B,
        const TrilinosWrappers::MPI::Vector     &gamma_W,
        const TrilinosWrappers::PreconditionAMG &amg,
        const TrilinosWrappers::MPI::Vector     &p_template)
        : B(B)
        , gamma_W(gamma_W)
        , amg(amg)
        , residual(p_template)
      {}

      void
      vmult(TrilinosWrappers::MPI::BlockVector       &dst,
            const TrilinosWrappers::MPI::BlockVector &src) const
      {
        dst.block(1) = src.block(1);
        dst.block(1).scale(gamma_W);
        dst.block(1) *= -1.;
        B.Tvmult(residual, dst.block(1));
        residual.sadd(-1., 1., src.block(0));
        amg.vmult(dst.block(0), residual);
      }

    private:
      const TrilinosWrappers::SparseMatrix    &B;
      const TrilinosWrappers::MPI::Vector     &gamma_W;
      const TrilinosWrappers::PreconditionAMG &amg;
      mutable TrilinosWrappers::MPI::Vector    residual;
    };

  } // namespace
} // namespace rbc_ifem

namespace rbc_ifem
{
  CODiffusion::CODiffusion(
    const DiffusionParameters                 &parameters,
    const std::function<double(unsigned int)> &permeability,
    const types::boundary_id                   pressure_boundary,
    const MPI_Comm                             communicator,
    TimerOutput                               &timer,
    const std::optional<double>               &period)
    : DiffusionSolver(parameters.alveolar_pressure)
    , parameters(parameters)
    , permeability(permeability)
    , pressure_boundary(pressure_boundary)
    , period(period)
    , communicator(communicator)
    , timer(timer)
    , fe(parameters.degree)
    , mapping(parameters.degree)
    , multiplier_fe(1)
  {}

  CODiffusion::~CODiffusion() = default;

  MembranesFinerThanMesh::MembranesFinerThanMesh(
    const double membrane_cell_size,
    const double volume_cell_size)
    : std::runtime_error("membrane cells finer than the diffusion mesh")
    , membrane_cell_size(membrane_cell_size)
    , volume_cell_size(volume_cell_size)
  {}

  void
  CODiffusion::setup(const parallel::TriangulationBase<3> &mesh,
                     const MembraneSurfaces               &membranes)
  {
    TimerOutput::Scope scope(timer, "diffusion: setup");
    this->mesh =
      dynamic_cast<const parallel::shared::Triangulation<3> *>(&mesh);
    AssertThrow(this->mesh != nullptr,
                ExcMessage("CODiffusion needs a parallel::shared::"
                           "Triangulation: every rank locates every membrane "
                           "point in it."));
    this->membranes        = membranes.meshes();
    this->membrane_mapping = &membranes.mapping();

    dof_handler.reinit(*this->mesh);
    dof_handler.distribute_dofs(fe);
    owned_dofs = dof_handler.locally_owned_dofs();
    make_pressure_constraints(dof_handler,
                              mapping,
                              pressure_boundary,
                              parameters.alveolar_pressure,
                              period,
                              constraints);
    setup_multipliers();
    locate_membrane_points();
    setup_matrices();
  }


  double
  CODiffusion::dm_total() const
  {
    return flow_per_pressure();
  }

  void
  CODiffusion::setup_multipliers()
  {
    multiplier_dof_handlers.clear();
    multiplier_offsets = {0};
    for (const Triangulation<2, 3> *membrane : membranes)
      {
        multiplier_dof_handlers.push_back(
          std::make_unique<DoFHandler<2, 3>>(*membrane));
        multiplier_dof_handlers.back()->distribute_dofs(multiplier_fe);
        multiplier_offsets.push_back(multiplier_offsets.back() +
                                     multiplier_dof_handlers.back()->n_dofs());
      }
    // The multipliers are few (a few thousand per cell): every rank knows
    // them all, and owns a contiguous share of the rows.
    const types::global_dof_index n = multiplier_offsets.back();
    const unsigned int rank    = Utilities::MPI::this_mpi_process(communicator);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    owned_multipliers          = IndexSet(n);
    owned_multipliers.add_range(n * rank / n_ranks, n * (rank + 1) / n_ranks);
  }

  std::vector<Point<3>>
  CODiffusion::membrane_quadrature_points()
  {
    FEValues<2, 3>        fe_values(*membrane_mapping,
                             multiplier_fe,
                             coupling->quadrature,
                             update_quadrature_points | update_JxW_values);
    std::vector<Point<3>> points;
    for (unsigned int m = 0; m < membranes.size(); ++m)
      for (const auto &cell :
           multiplier_dof_handlers[m]->active_cell_iterators())
        {
          fe_values.reinit(cell);
          for (const Point<3> &p : fe_values.get_quadrature_points())
            points.push_back(wrap_into_segment(p, period));
          coupling->JxW.push_back(fe_values.get_JxW_values());
          std::vector<types::global_dof_index> dofs(
            multiplier_fe.n_dofs_per_cell());
          cell->get_dof_indices(dofs);
          for (auto &dof : dofs)
            dof += multiplier_offsets[m];
          coupling->multiplier_dofs.push_back(dofs);
        }
    return points;
  }

  void
  CODiffusion::locate_membrane_points()
  {
    coupling                           = std::make_unique<CouplingData>();
    const std::vector<Point<3>> points = membrane_quadrature_points();
    if (points.empty())
      return;

    TimerOutput::Scope        scope(timer, "diffusion: point location");
    const GridTools::Cache<3> cache(*mesh, mapping);
    const unsigned int        n_q = coupling->quadrature.size();
    // Consecutive points lie on one membrane cell, so the cell of the last
    // point is the best first guess for the next: 10 times faster than
    // GridTools::compute_point_locations() at a million cells.
    Triangulation<3>::active_cell_iterator hint;
    for (unsigned int k = 0; k < points.size(); ++k)
      {
        const auto [cell, reference] =
          GridTools::find_active_cell_around_point(cache, points[k], hint);
        if (cell == Triangulation<3>::active_cell_iterator())
          {
            std::ostringstream where;
            where << "membrane point (" << points[k] << ')';
            throw InputError(
              "Layout",
              where.str(),
              "this point lies outside the diffusion mesh; every "
              "cell must lie inside the capillary.");
          }
        hint = cell;
        coupling->points.push_back(
          {k / n_q,
           k % n_q,
           typename DoFHandler<3>::active_cell_iterator(
             &*mesh, cell->level(), cell->index(), &dof_handler),
           reference});
      }
    std::sort(coupling->points.begin(),
              coupling->points.end(),
              [](const CouplingData::Point &a, const CouplingData::Point &b) {
                return std::make_pair(a.membrane_cell,
                                      a.volume_cell->active_cell_index()) <
                       std::make_pair(b.membrane_cell,
                                      b.volume_cell->active_cell_index());
              });
    check_inf_sup();
  }

  void
  CODiffusion::check_inf_sup()
  {
    // The multiplier space must not be finer than the volume mesh around
    // it (the inf-sup condition of the saddle point problem): with membrane
    // cells 1.7 times smaller FGMRES no longer converges.
    double area = 0.;
    for (const std::vector<double> &JxW : coupling->JxW)
      for (const double dA : JxW)
        area += dA;
    const double membrane_cell_size = std::sqrt(area / coupling->JxW.size());
    double       volume_cell_size   = 0.;
    coupling->for_each_run([&](const unsigned int,
                               const auto &cell,
                               const auto &first,
                               const auto &last) {
      volume_cell_size += (last - first) * cell->diameter() / std::sqrt(3.);
    });
    volume_cell_size /= coupling->points.size();
    if (volume_cell_size > 1.4 * membrane_cell_size)
      throw MembranesFinerThanMesh(membrane_cell_size, volume_cell_size);

    constraint_scale =
      permeability(coupling->points.front().volume_cell->material_id()) /
      membrane_cell_size;
  }

  void
  CODiffusion::setup_matrices()
  {
    const types::global_dof_index n_multipliers = multiplier_offsets.back();
    const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);

    // B with every row, on every rank: it is small, and its rows tell which
    // P DoFs the augmentation Bᵀ W B couples.
    AffineConstraints<double> no_constraints;
    no_constraints.close();
    DynamicSparsityPattern b_pattern(n_multipliers, dof_handler.n_dofs());
    std::vector<types::global_dof_index> volume_dofs(fe.n_dofs_per_cell());
    coupling->for_each_run([&](const unsigned int membrane_cell,
                               const auto        &volume_cell,
                               const auto &,
                               const auto &) {
      volume_cell->get_dof_indices(volume_dofs);
      for (const auto dof : volume_dofs)
        AssertThrow(!constraints.is_inhomogeneously_constrained(dof),
                    ExcMessage(
                      "a membrane touches the boundary where P = P_A"));
      no_constraints.add_entries_local_to_global(
        coupling->multiplier_dofs[membrane_cell],
        constraints,
        volume_dofs,
        b_pattern,
        false);
    });

    IndexSet relevant_dofs;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    TrilinosWrappers::SparsityPattern a_pattern(owned_dofs,
                                                owned_dofs,
                                                relevant_dofs,
                                                communicator);
    DoFTools::make_sparsity_pattern(
      dof_handler, a_pattern, constraints, false, rank);
    TrilinosWrappers::SparsityPattern c_pattern(owned_multipliers,
                                                owned_dofs,
                                                communicator);
    for (types::global_dof_index i = 0; i < n_multipliers; ++i)
      {
        std::vector<types::global_dof_index> columns;
        for (auto entry = b_pattern.begin(i); entry != b_pattern.end(i);
             ++entry)
          columns.push_back(entry->column());
        if (owned_multipliers.is_element(i))
          c_pattern.add_entries(i, columns.begin(), columns.end());
        for (const auto j : columns)
          if (owned_dofs.is_element(j))
            a_pattern.add_entries(j, columns.begin(), columns.end());
      }
    a_pattern.compress();
    c_pattern.compress();
    stiffness.reinit(a_pattern);
    coupling_matrix.reinit(c_pattern);
    coupling_sparsity.copy_from(b_pattern);
    full_coupling_matrix.reinit(coupling_sparsity);

    solution.reinit({owned_dofs, owned_multipliers}, communicator);
    rhs.reinit({owned_dofs, owned_multipliers}, communicator);
    multiplier_weights.reinit(owned_multipliers, communicator);
  }

  void
  CODiffusion::assemble()
  {
    TimerOutput::Scope scope(timer, "diffusion: assemble");
    stiffness            = 0.;
    rhs                  = 0.;
    coupling_matrix      = 0.;
    full_coupling_matrix = 0.;
    assemble_stiffness();
    assemble_coupling();
    assemble_augmentation();

    TimerOutput::Scope amg_scope(timer, "diffusion: AMG setup");
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    amg_data.elliptic              = true;
    amg_data.higher_order_elements = fe.degree > 1;
    amg_data.smoother_sweeps       = 2;
    amg_data.aggregation_threshold = 0.02;
    amg.initialize(stiffness, amg_data);
  }

  void
  CODiffusion::assemble_stiffness()
  {
    const QGauss<3>                      quadrature(fe.degree + 1);
    FEValues<3>                          fe_values(mapping,
                          fe,
                          quadrature,
                          update_gradients | update_JxW_values);
    const unsigned int                   n = fe.n_dofs_per_cell();
    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          const double alpha_D = permeability(cell->material_id());
          cell_matrix          = 0.;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                cell_matrix(i, j) += alpha_D * fe_values.shape_grad(i, q) *
                                     fe_values.shape_grad(j, q) *
                                     fe_values.JxW(q);
          cell->get_dof_indices(dofs);
          constraints.distribute_local_to_global(
            cell_matrix, cell_rhs, dofs, stiffness, rhs.block(0));
        }
    stiffness.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }

  void
  CODiffusion::assemble_coupling()
  {
    AffineConstraints<double> no_constraints;
    no_constraints.close();
    const unsigned int                   n_mu = multiplier_fe.n_dofs_per_cell();
    const unsigned int                   n_p  = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> volume_dofs(n_p);
    coupling->for_each_run([&](const unsigned int membrane_cell,
                               const auto        &volume_cell,
                               const auto        &first,
                               const auto        &last) {
      FullMatrix<double> local(n_mu, n_p);
      for (auto point = first; point != last; ++point)
        {
          const double dA =
            constraint_scale * coupling->JxW[membrane_cell][point->q];
          const Point<2> &xi = coupling->quadrature.point(point->q);
          for (unsigned int j = 0; j < n_p; ++j)
            {
              const double phi = fe.shape_value(j, point->reference) * dA;
              for (unsigned int i = 0; i < n_mu; ++i)
                local(i, j) += multiplier_fe.shape_value(i, xi) * phi;
            }
        }
      volume_cell->get_dof_indices(volume_dofs);
      no_constraints.distribute_local_to_global(
        local,
        coupling->multiplier_dofs[membrane_cell],
        constraints,
        volume_dofs,
        full_coupling_matrix);
    });
    // The distributed copy holds the rows this rank owns.
    for (const auto i : owned_multipliers)
      for (auto entry = full_coupling_matrix.begin(i);
           entry != full_coupling_matrix.end(i);
           ++entry)
        coupling_matrix.set(i, entry->column(), entry->value());
    coupling_matrix.compress(VectorOperation::insert);

    // Lumped membrane mass m_i = ∫ μ_i dA; W = diag(1 / (σ m_i)).
    multiplier_mass.reinit(multiplier_offsets.back());
    const unsigned int n_q = coupling->quadrature.size();
    for (unsigned int c = 0; c < coupling->JxW.size(); ++c)
      for (unsigned int q = 0; q < n_q; ++q)
        for (unsigned int i = 0; i < n_mu; ++i)
          multiplier_mass[coupling->multiplier_dofs[c][i]] +=
            multiplier_fe.shape_value(i, coupling->quadrature.point(q)) *
            coupling->JxW[c][q];
    for (const auto i : owned_multipliers)
      multiplier_weights[i] =
        parameters.augmentation / (constraint_scale * multiplier_mass[i]);
    multiplier_weights.compress(VectorOperation::insert);
  }

  void
  CODiffusion::assemble_augmentation()
  {
    // A_γ = A + Bᵀ (γW) B, row by row of B: every pair of P DoFs in row i
    // couples with weight γ W_i B_ij B_ik. (Trilinos' Tmmult would do this
    // product, but crashes on more than one rank in deal.II 9.4.)
    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    for (types::global_dof_index i = 0; i < full_coupling_matrix.m(); ++i)
      {
        const double weight =
          parameters.augmentation / (constraint_scale * multiplier_mass[i]);
        for (auto row = full_coupling_matrix.begin(i);
             row != full_coupling_matrix.end(i);
             ++row)
          if (owned_dofs.is_element(row->column()))
            {
              columns.clear();
              values.clear();
              for (auto entry = full_coupling_matrix.begin(i);
                   entry != full_coupling_matrix.end(i);
                   ++entry)
                {
                  columns.push_back(entry->column());
                  values.push_back(weight * row->value() * entry->value());
                }
              stiffness.add(row->column(),
                            columns.size(),
                            columns.data(),
                            values.data());
            }
      }
    stiffness.compress(VectorOperation::add);
  }

  void
  CODiffusion::solve()
  {
    TimerOutput::Scope scope(timer, "diffusion: solve");
    // S = diag(A_γ)^-1/2 on P, W^1/2 on λ: both rows O(1) on the diagonal.
    TrilinosWrappers::MPI::BlockVector scale(rhs), inverse_scale(rhs);
    for (const auto i : owned_dofs)
      scale.block(0)[i] = 1. / std::sqrt(stiffness.diag_element(i));
    for (const auto i : owned_multipliers)
      scale.block(1)[i] =
        std::sqrt(multiplier_weights[i] / parameters.augmentation);
    scale.compress(VectorOperation::insert);
    for (unsigned int b = 0; b < 2; ++b)
      for (const auto i : scale.block(b).locally_owned_elements())
        inverse_scale.block(b)[i] = 1. / scale.block(b)[i];
    inverse_scale.compress(VectorOperation::insert);

    const SaddlePointOperator               op(stiffness, coupling_matrix);
    const AugmentedLagrangianPreconditioner preconditioner(coupling_matrix,
                                                           multiplier_weights,
                                                           amg,
                                                           rhs.block(0));
    TrilinosWrappers::MPI::BlockVector      scaled_rhs(rhs);
    scaled_rhs.scale(scale);
    SolverControl control(parameters.max_linear_iterations,
                          parameters.linear_tolerance * scaled_rhs.l2_norm());
    SolverFGMRES<TrilinosWrappers::MPI::BlockVector> solver(
      control,
      SolverFGMRES<TrilinosWrappers::MPI::BlockVector>::AdditionalData(100));
    solution = 0.;
    try
      {
        solver.solve(
          DiagonallyScaled<SaddlePointOperator,
                           TrilinosWrappers::MPI::BlockVector>(op, scale),
          solution,
          scaled_rhs,
          DiagonallyScaled<AugmentedLagrangianPreconditioner,
                           TrilinosWrappers::MPI::BlockVector>(preconditioner,
                                                               inverse_scale));
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw no_convergence("CO diffusion: FGMRES",
                             e,
                             control.tolerance(),
                             "Raise Diffusion/Max linear iterations, or check "
                             "that the membranes are resolved by the mesh.");
      }
    solution.scale(scale);
    iterations = control.last_step();
    if (!std::isfinite(solution.l2_norm()))
      throw SolverFailure("CO diffusion: the solution is not finite.");
    constraints.distribute(solution.block(0));
    compute_flows();
  }

  void
  CODiffusion::compute_flows()
  {
    // λ = σ λ_s: the unknown is the multiplier of the scaled rows σ B.
    TrilinosWrappers::MPI::Vector all(owned_multipliers,
                                      complete_index_set(
                                        multiplier_offsets.back()),
                                      communicator);
    all = solution.block(1);
    multiplier_values.reinit(multiplier_offsets.back());
    for (types::global_dof_index i = 0; i < multiplier_values.size(); ++i)
      multiplier_values[i] = constraint_scale * all[i];

    flows.assign(membranes.size(), 0.);
    for (unsigned int m = 0; m < membranes.size(); ++m)
      for (auto i = multiplier_offsets[m]; i < multiplier_offsets[m + 1]; ++i)
        flows[m] += multiplier_values[i] * multiplier_mass[i];

    // The flow through the alveolar surface equals ∫ λ because
    // a(P, 1) = 0.
    IndexSet relevant_dofs;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    TrilinosWrappers::MPI::Vector P(owned_dofs, relevant_dofs, communicator);
    P             = solution.block(0);
    alveolar_flow = flow_through_boundary(
      dof_handler, mapping, P, pressure_boundary, permeability, communicator);
  }

  types::global_dof_index
  CODiffusion::n_pressure_dofs() const
  {
    return dof_handler.n_dofs();
  }

  types::global_dof_index
  CODiffusion::n_multiplier_dofs() const
  {
    return multiplier_offsets.back();
  }

  types::global_dof_index
  CODiffusion::n_dofs() const
  {
    return n_pressure_dofs() + n_multiplier_dofs();
  }

  CODiffusion::OutputFiles
  CODiffusion::write_output(const std::string &directory,
                            const std::string &name,
                            const unsigned int counter,
                            const FieldData   &field_data) const
  {
    TimerOutput::Scope scope(timer, "diffusion: output");
    IndexSet           relevant_dofs;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    TrilinosWrappers::MPI::Vector P(owned_dofs, relevant_dofs, communicator);
    P = solution.block(0);

    Vector<float> material_id(mesh->n_active_cells());
    for (const auto &cell : mesh->active_cell_iterators())
      material_id[cell->active_cell_index()] = cell->material_id();
    DataOut<3> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.set_flags(fast_vtk_flags());
    data_out.add_data_vector(P, "co_pressure");
    data_out.add_data_vector(material_id,
                             "material_id",
                             DataOut<3>::type_cell_data);
    data_out.build_patches(mapping, fe.degree);
    std::vector<Vector<double>> flux(membranes.size());
    for (unsigned int m = 0; m < membranes.size(); ++m)
      {
        flux[m].reinit(multiplier_dof_handlers[m]->n_dofs());
        for (unsigned int i = 0; i < flux[m].size(); ++i)
          flux[m][i] = multiplier_values[multiplier_offsets[m] + i];
      }
    return write_fields(data_out,
                        membranes,
                        *membrane_mapping,
                        multiplier_dof_handlers,
                        flux,
                        directory,
                        name,
                        counter,
                        communicator,
                        field_data,
                        "co_flux");
  }
} // namespace rbc_ifem

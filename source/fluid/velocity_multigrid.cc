#include <rbc_ifem/fluid/velocity_multigrid.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/multigrid/mg_coarse.h>

namespace rbc_ifem
{
  /**
   * The coarsest level's solve: one V-cycle of algebraic multigrid
   * (Trilinos ML) on the assembled operator, each rank its part. An LU
   * (Amesos KLU) gathered the whole coarse matrix on rank 0 and factorised
   * it there: rank 0 then held about 90 MB more than the other ranks in
   * the 320 µm segment (doc/scaling.md, Section 3), a share that grows with
   * the capillary's length on one rank alone. The V-cycle costs a few
   * more FGMRES iterations than the LU did; CG with this AMG to 1e-6 saved
   * some of them but tripled the collectives per step with its inner
   * products (doc/scaling.md, Section 3, the measured counts).
   */
  class VelocityMultigrid::CoarseSolver
    : public MGCoarseGridBase<VelocityVector>
  {
  public:
    CoarseSolver(const VelocityOperator          &coarse_operator,
                 const AffineConstraints<double> &constraints,
                 const DoFHandler<3>             &dof_handler)
    {
      coarse_operator.assemble_matrix(constraints, matrix);
      TrilinosWrappers::PreconditionAMG::AdditionalData settings;
      settings.elliptic              = true;
      settings.higher_order_elements = true;
      settings.smoother_sweeps       = 2;
      DoFTools::extract_constant_modes(dof_handler,
                                       ComponentMask(),
                                       settings.constant_modes);
      amg.initialize(matrix, settings);
    }

    void
    operator()(const unsigned int,
               VelocityVector       &dst,
               const VelocityVector &src) const override
    {
      amg.vmult(dst, src);
    }

  private:
    TrilinosWrappers::SparseMatrix    matrix;
    TrilinosWrappers::PreconditionAMG amg;
  };


  VelocityMultigrid::VelocityMultigrid(
    const std::vector<std::shared_ptr<const Triangulation<3>>> &coarser_meshes,
    const Mapping<3>                                           &mapping,
    std::shared_ptr<const MatrixFree<3, double>> fine_matrix_free,
    const unsigned int                           fine_dof_index,
    const AffineConstraints<double>             &fine_constraints,
    const ConstraintMaker                       &make_constraints)
  {
    const unsigned int   fine = coarser_meshes.size();
    const DoFHandler<3> &fine_dof_handler =
      fine_matrix_free->get_dof_handler(fine_dof_index);
    dof_handlers.resize(0, fine);
    constraints.resize(0, fine);
    level_dofs.resize(0, fine);
    level_constraints.resize(0, fine);
    operators.resize(0, fine);
    transfers.resize(0, fine);

    typename MatrixFree<3, double>::AdditionalData data;
    data.tasks_parallel_scheme = MatrixFree<3, double>::AdditionalData::none;
    data.mapping_update_flags =
      update_values | update_gradients | update_JxW_values;
    const QGauss<1> quadrature(3);
    for (unsigned int level = 0; level < fine; ++level)
      {
        dof_handlers[level].reinit(*coarser_meshes[level]);
        dof_handlers[level].distribute_dofs(fine_dof_handler.get_fe());
        make_constraints(dof_handlers[level], constraints[level]);
        auto matrix_free = std::make_shared<MatrixFree<3, double>>();
        matrix_free->reinit(
          mapping, dof_handlers[level], constraints[level], quadrature, data);
        operators[level] =
          std::make_unique<VelocityOperator>(std::move(matrix_free), 0);
        level_dofs[level]        = &dof_handlers[level];
        level_constraints[level] = &constraints[level];
      }
    operators[fine] =
      std::make_unique<VelocityOperator>(fine_matrix_free, fine_dof_index);
    level_dofs[fine]        = &fine_dof_handler;
    level_constraints[fine] = &fine_constraints;

    for (unsigned int level = 1; level <= fine; ++level)
      transfers[level].reinit(*level_dofs[level],
                              *level_dofs[level - 1],
                              *level_constraints[level],
                              *level_constraints[level - 1]);
    transfer = std::make_unique<Transfer>(
      transfers, [this](const unsigned int level, VelocityVector &v) {
        operators[level]->initialize_dof_vector(v);
      });
  }

  VelocityMultigrid::~VelocityMultigrid() = default;

  void
  VelocityMultigrid::set_coefficients(const double mass_factor,
                                      const double viscosity)
  {
    for (unsigned int level = 0; level <= operators.max_level(); ++level)
      operators[level]->set_coefficients(mass_factor, viscosity);
    coarse = std::make_unique<CoarseSolver>(*operators[0],
                                            *level_constraints[0],
                                            dof_handlers[0]);
    build_cycle(20);
  }

  void
  VelocityMultigrid::set_added_terms(
    const std::vector<VelocityOperator::AddedTerm> &terms,
    const std::vector<VelocityVector>              &diagonals)
  {
    AssertDimension(terms.size(), n_levels());
    for (unsigned int level = 0; level <= operators.max_level(); ++level)
      operators[level]->set_added_term(terms[level], diagonals[level]);
    // Every step: the largest eigenvalue from 8 CG steps, within the
    // smoother's 1.2 margin; 20 took a sixth of a stiff run's fluid solve
    // (K = 500, Δt = 4e-5 s) and saved no outer iteration.
    build_cycle(8);
  }

  const DoFHandler<3> &
  VelocityMultigrid::level_dof_handler(const unsigned int level) const
  {
    return *level_dofs[level];
  }

  const AffineConstraints<double> &
  VelocityMultigrid::level_zero_constraints(const unsigned int level) const
  {
    return *level_constraints[level];
  }

  void
  VelocityMultigrid::initialize_level_vector(const unsigned int level,
                                             VelocityVector    &v) const
  {
    operators[level]->initialize_dof_vector(v);
  }

  void
  VelocityMultigrid::build_cycle(const unsigned int eigenvalue_iterations)
  {
    const unsigned int                      fine = operators.max_level();
    MGLevelObject<Smoother::AdditionalData> smoother_data(0, fine);
    for (unsigned int level = 0; level <= fine; ++level)
      {
        // Chebyshev of degree 2 on the upper part [λ_max/20, 1.2 λ_max] of
        // the spectrum of D⁻¹A: the part the coarser levels cannot see.
        smoother_data[level].preconditioner =
          operators[level]->inverse_diagonal();
        smoother_data[level].degree              = 2;
        smoother_data[level].smoothing_range     = 20.;
        smoother_data[level].eig_cg_n_iterations = eigenvalue_iterations;
      }
    smoother.initialize(operators, smoother_data);

    level_matrices = std::make_unique<mg::Matrix<VelocityVector>>(operators);
    multigrid      = std::make_unique<Multigrid<VelocityVector>>(
      *level_matrices, *coarse, *transfer, smoother, smoother, 0, fine);
    v_cycle = std::make_unique<PreconditionMG<3, VelocityVector, Transfer>>(
      *level_dofs[fine], *multigrid, *transfer);
  }

  void
  VelocityMultigrid::vmult(VelocityVector &dst, const VelocityVector &src) const
  {
    v_cycle->vmult(dst, src);
  }

  unsigned int
  VelocityMultigrid::n_levels() const
  {
    return operators.max_level() + 1;
  }

  std::vector<types::global_dof_index>
  VelocityMultigrid::n_dofs_per_level() const
  {
    std::vector<types::global_dof_index> n_dofs;
    for (unsigned int level = 0; level <= operators.max_level(); ++level)
      n_dofs.push_back(level_dofs[level]->n_dofs());
    return n_dofs;
  }
} // namespace rbc_ifem

#include <rbc_ifem/diffusion/scaled_amg_solve.h>

#include <deal.II/lac/solver_cg.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <cmath>
#include <memory>

namespace rbc_ifem
{
  void
  initialize_uptake_amg(TrilinosWrappers::PreconditionAMG    &amg,
                        const TrilinosWrappers::SparseMatrix &matrix,
                        const unsigned int                    degree)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData amg_data;
    amg_data.elliptic              = true;
    amg_data.higher_order_elements = degree > 1;
    amg_data.smoother_sweeps       = 2;
    amg_data.aggregation_threshold = 0.02;
    // The coarsest level (deal.II's set_parameters() asks ML for at most
    // 2000 rows) is factorised by KLU at every setup and solved at every
    // V-cycle; coarsening on to 500 rows is cheaper than both, and the
    // seven-cell solve's setup and solve together take a quarter less
    // (43 CG iterations instead of 42, doc/diffusion.md).
    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    amg_data.set_parameters(ml_parameters, constant_modes, matrix);
    ml_parameters.set("coarse: max size", 500);
    amg.initialize(matrix, ml_parameters);
  }

  void
  solve_scaled_cg(const TrilinosWrappers::SparseMatrix    &matrix,
                  const TrilinosWrappers::PreconditionAMG &amg,
                  const IndexSet                          &owned_dofs,
                  const TrilinosWrappers::MPI::Vector     &rhs,
                  TrilinosWrappers::MPI::Vector           &x,
                  SolverControl                           &control)
  {
    x.reinit(rhs);
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    solve_scaled(cg, matrix, amg, owned_dofs, rhs, x, control);
  }
} // namespace rbc_ifem

#ifndef rbc_ifem_diffusion_binding_preconditioner_h
#define rbc_ifem_diffusion_binding_preconditioner_h

#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <utility>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * A preconditioner for a time step of O2 with hemoglobin binding
   * (CutCellOxygen): the matrix
   *
   *   A = [ A_PP  B ]   P: every pressure DoF, S: the saturation DoFs,
   *       [ E  A_SS ]   B, E: the binding, one entry per node (P₁, S),
   *
   * is symmetric but for B and E, and once the binding is fast B is far
   * larger than A_PP's diagonal (C q_S against α/Δt): AMG of A itself
   * fails. The block factorisation with S eliminated node by node,
   *
   *   y_P = Ŝ⁻¹ (r_P − B D⁻¹ r_S),   y_S = A_SS⁻¹ (r_S − E y_P),
   *
   * D the diagonal of A_SS and Ŝ = A_PP − B D⁻¹ E (A_PP's diagonal
   * shifted by −BE/D = w² q_S q_P / D ≤ 0, which leaves it larger than
   * without the binding: w q_P (D − w|q_S|)/D ≥ 0 is what remains of the
   * binding's share), is exact but for D standing in for A_SS; Ŝ and A_SS
   * are the two blocks of one symmetric positive definite matrix, A
   * without B and E and with the shift, and one AMG V-cycle of it applies
   * both at once: its S part is A_SS⁻¹ r_S, to which −D⁻¹ E y_P is added
   * (D again for A_SS). One V-cycle per application.
   */
  class BindingPreconditioner
  {
  public:
    /**
     * Set up for @p matrix, whose binding couples the DoFs of each of
     * @p pairs (P₁, S; rows owned here), with AMG for elements of degree
     * @p degree.
     */
    void
    initialize(const TrilinosWrappers::SparseMatrix                  &matrix,
               const std::vector<std::pair<types::global_dof_index,
                                           types::global_dof_index>> &pairs,
               const unsigned int                                     degree);

    /// dst = the preconditioner applied to src.
    void
    vmult(TrilinosWrappers::MPI::Vector       &dst,
          const TrilinosWrappers::MPI::Vector &src) const;

  private:
    /// A node's binding: its DoFs and B, E and D there.
    struct Node
    {
      types::global_dof_index pressure, saturation;
      double                  b, e, d;
    };
    std::vector<Node>                 nodes;
    TrilinosWrappers::SparseMatrix    decoupled;
    TrilinosWrappers::PreconditionAMG amg;
  };
} // namespace rbc_ifem

#endif

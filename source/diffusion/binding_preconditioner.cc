#include <rbc_ifem/diffusion/binding_preconditioner.h>
#include <rbc_ifem/diffusion/scaled_amg_solve.h>

namespace rbc_ifem
{
  void
  BindingPreconditioner::initialize(
    const TrilinosWrappers::SparseMatrix &matrix,
    const std::vector<
      std::pair<types::global_dof_index, types::global_dof_index>> &pairs,
    const unsigned int                                              degree)
  {
    nodes.clear();
    for (const auto &[p, s] : pairs)
      nodes.push_back(
        {p, s, matrix.el(p, s), matrix.el(s, p), matrix.el(s, s)});
    // A without the binding's coupling, Ŝ's shift on P₁'s diagonal.
    // (matrix's graph and values; only owned rows change here.)
    decoupled.reinit(matrix.trilinos_matrix(), true);
    for (const Node &node : nodes)
      {
        decoupled.set(node.pressure, node.saturation, 0.);
        decoupled.set(node.saturation, node.pressure, 0.);
      }
    decoupled.compress(VectorOperation::insert);
    for (const Node &node : nodes)
      decoupled.add(node.pressure, node.pressure, -node.b * node.e / node.d);
    decoupled.compress(VectorOperation::add);
    initialize_uptake_amg(amg, decoupled, degree);
  }

  void
  BindingPreconditioner::vmult(TrilinosWrappers::MPI::Vector       &dst,
                               const TrilinosWrappers::MPI::Vector &src) const
  {
    // y_P from r_P − B D⁻¹ r_S.
    TrilinosWrappers::MPI::Vector reduced(src);
    for (const Node &node : nodes)
      reduced[node.pressure] -= node.b / node.d * src[node.saturation];
    reduced.compress(VectorOperation::add);
    amg.vmult(dst, reduced);
    // The V-cycle acts on P and S apart (the decoupled matrix has no entry
    // between them), so dst's S part is A_SS⁻¹ r_S; y_S = A_SS⁻¹ (r_S −
    // E y_P) takes the correction with D for A_SS, as Ŝ does.
    for (const Node &node : nodes)
      dst[node.saturation] -= node.e / node.d * dst[node.pressure];
    dst.compress(VectorOperation::add);
  }
} // namespace rbc_ifem

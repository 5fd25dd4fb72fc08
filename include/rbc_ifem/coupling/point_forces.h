#ifndef rbc_ifem_coupling_point_forces_h
#define rbc_ifem_coupling_point_forces_h

#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * @name Forces on single membrane points
   *
   * What the CellForce classes that act point by point (contact_forces.h,
   * pushing_force.h) share: a point is a node of a cell's Membrane, its
   * position and force the entries of its DoFs (Membrane::nodes()) in the
   * cell's Vector, and its weight the reference area it stands for.
   */
  /** @{ */

  /// The reference area a_i = ∫ N_i dA0 of every point of every cell.
  inline std::vector<std::vector<double>>
  reference_point_areas(const std::vector<std::shared_ptr<Membrane>> &membranes)
  {
    std::vector<std::vector<double>> areas;
    for (const auto &membrane : membranes)
      areas.push_back(membrane->nodal_areas(membrane->reference_positions()));
    return areas;
  }

  /// The position of the node with the DoFs @p dofs in a cell's positions
  /// @p x.
  inline Point<3>
  node_position(const Vector<double>                         &x,
                const std::array<types::global_dof_index, 3> &dofs)
  {
    return Point<3>(x[dofs[0]], x[dofs[1]], x[dofs[2]]);
  }

  /// Add @p force to the entries of the node with the DoFs @p dofs in a
  /// cell's @p forces.
  inline void
  add_node_force(Vector<double>                               &forces,
                 const std::array<types::global_dof_index, 3> &dofs,
                 const Tensor<1, 3>                           &force)
  {
    for (unsigned int d = 0; d < 3; ++d)
      forces[dofs[d]] += force[d];
  }

  /** @} */
} // namespace rbc_ifem

#endif

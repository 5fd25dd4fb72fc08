#ifndef rbc_ifem_coupling_pushing_force_h
#define rbc_ifem_coupling_pushing_force_h

#include <rbc_ifem/coupling/cell_force.h>
#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * A constant force on each cell (the pushing forces of Immersed cells),
   * spread over its points by their reference areas: E = -Σ_c F_c · Σ_i
   * (a_i / A_c) x_i. External.
   */
  class PushingForce : public CellForce
  {
  public:
    /// Each rank adds the forces on the cells of its @p owners (held by
    /// reference).
    PushingForce(const std::vector<std::shared_ptr<Membrane>> &membranes,
                 const std::vector<Tensor<1, 3>>              &cell_forces,
                 const CellOwners                             &owners);

    CellForceReport
    add_forces(const std::vector<Vector<double>> &positions,
               std::vector<Vector<double>>       &forces) const override;

    std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &positions) const override;

  private:
    const std::vector<std::shared_ptr<Membrane>> &membranes;
    const std::vector<Tensor<1, 3>>               cell_forces;
    const CellOwners                             &owners;
    /// a_i / A_c of every point.
    std::vector<std::vector<double>> weights;
  };
} // namespace rbc_ifem

#endif

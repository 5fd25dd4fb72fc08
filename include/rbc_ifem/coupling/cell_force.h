#ifndef rbc_ifem_coupling_cell_force_h
#define rbc_ifem_coupling_cell_force_h

#include <deal.II/base/tensor.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// What one CellForce did at the positions it was given.
  struct CellForceReport
  {
    double energy = 0.; ///< E(x) [pN µm]
    /**
     * The net force it exerts on the cells [pN]: an external force's (a
     * tether, a wall) holds them; an internal force (a membrane's elasticity,
     * two cells pushing each other) sums to zero, and reports zero.
     */
    Tensor<1, 3> external_force;
  };

  /**
   * The tangent stiffness K = ∂²E/∂x² of one CellForce at the positions it
   * was taken at (CellForce::stiffness()): the forces at x + δx are
   * F(x) - K δx to first order. The semi-implicit coupling applies it to
   * displacements of all cells.
   */
  class CellForceStiffness
  {
  public:
    virtual ~CellForceStiffness() = default;

    /// Add K @p displacements to @p results (one Vector per cell, in the
    /// layout of the positions), the rows of the cells this rank owns.
    virtual void
    add_product(const std::vector<Vector<double>> &displacements,
                std::vector<Vector<double>>       &results) const = 0;

    /// Add the diagonal of K to @p diagonal (one Vector per cell, in the
    /// layout of the positions), the rows of the cells this rank owns.
    virtual void
    add_diagonal(std::vector<Vector<double>> &diagonal) const = 0;

    /**
     * Mark in @p cells (one flag per cell) the cells other than this
     * rank's own whose displacements add_product() reads (a pair's
     * partner across two owners). None by default.
     */
    virtual void
    mark_cells_read(std::vector<bool> & /*cells*/) const
    {}
  };

  /**
   * One contribution to the forces on the membrane points of a
   * CellPopulation: an energy E(x) of the positions x of all cells and its
   * exact negative gradient F = -∂E/∂x. The population sums every force it
   * holds (CellPopulation::add_force()); the coupling sees only the sum.
   *
   * Positions and forces come one Vector per cell, one entry per DoF of the
   * cell's Membrane (the x, y, z of each node: Membrane::nodes()). Forces
   * that involve several cells (a repulsion between them) see all of them;
   * since F is a gradient, the forces of a pair are equal and opposite.
   *
   * On several ranks each rank adds the forces, energy and products K v of
   * the cells it owns (CellOwners) and leaves the others' alone: the
   * population keeps them with the owners (CellPopulation::
   * compute_owned_forces(); compute_forces() adds them up over the ranks
   * in one reduction) and sums only the energy and the held force. A term
   * shared by two
   * cells of different owners (a pair's energy) counts half on each.
   */
  class CellForce
  {
  public:
    virtual ~CellForce() = default;

    /// Add F = -∂E/∂x at @p positions to @p forces [pN]; report E.
    virtual CellForceReport
    add_forces(const std::vector<Vector<double>> &positions,
               std::vector<Vector<double>>       &forces) const = 0;

    /**
     * The exact K = ∂²E/∂x² at @p positions; nullptr for a force that does
     * not change with the positions (K = 0). Tests check K δx against the
     * central difference of the forces (tests/unit/coupling/).
     */
    virtual std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &positions) const = 0;
  };
} // namespace rbc_ifem

#endif

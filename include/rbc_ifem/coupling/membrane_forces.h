#ifndef rbc_ifem_coupling_membrane_forces_h
#define rbc_ifem_coupling_membrane_forces_h

#include <rbc_ifem/coupling/cell_force.h>
#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/membrane/membrane.h>

#include <memory>
#include <vector>

namespace rbc_ifem
{
  /**
   * The membranes' own mechanics as a CellForce: every cell's Membrane
   * energy (in-plane law, bending, area and volume) and its exact forces.
   * Internal: it holds no cell in place. Each cell's forces and tangent
   * stiffness are computed by its owner rank alone; the CellPopulation
   * adds them up over the ranks.
   */
  class MembraneElasticity : public CellForce
  {
  public:
    /// The membranes of the cells, in the population's order, and the
    /// ranks that own them (held by reference: they may change later).
    MembraneElasticity(const std::vector<std::shared_ptr<Membrane>> &membranes,
                       const CellOwners                             &owners);

    CellForceReport
    add_forces(const std::vector<Vector<double>> &positions,
               std::vector<Vector<double>>       &forces) const override;

    std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &positions) const override;

  private:
    const std::vector<std::shared_ptr<Membrane>> &membranes;
    const CellOwners                             &owners;
  };

  /**
   * Springs that hold every membrane point at its reference position X:
   * E = k/2 |x - X|², F = -k (x - X). External: the force that holds the
   * cells (the drag's opposite) is flow.csv's held_force (Immersed
   * cells/Tether stiffness).
   */
  class Tether : public CellForce
  {
  public:
    /// Springs of @p stiffness on the @p membranes; each rank adds the
    /// forces on the cells it owns (@p owners, held by reference).
    Tether(const std::vector<std::shared_ptr<Membrane>> &membranes,
           const double                                  stiffness,
           const CellOwners                             &owners);

    CellForceReport
    add_forces(const std::vector<Vector<double>> &positions,
               std::vector<Vector<double>>       &forces) const override;

    std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &positions) const override;

  private:
    const std::vector<std::shared_ptr<Membrane>> &membranes;
    const double      spring_constant; ///< k [pN/µm]
    const CellOwners &owners;
  };
} // namespace rbc_ifem

#endif

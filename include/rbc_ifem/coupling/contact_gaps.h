#ifndef rbc_ifem_coupling_contact_gaps_h
#define rbc_ifem_coupling_contact_gaps_h

#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/lac/vector.h>

#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// How close one cell comes to the others and to the wall [µm].
  struct CellGaps
  {
    /**
     * The smallest gap from a point of this cell's membrane to any other
     * cell's membrane: the distance of the point from the tangent plane at
     * the other membrane's nearest point, negative where the point lies
     * inside the other cell (the membranes cross). Infinite when alone.
     */
    double to_cells = std::numeric_limits<double>::infinity();
    /// The smallest R - sqrt(y² + z²) of its points, negative outside the
    /// lumen; infinite where there is no wall.
    double to_wall = std::numeric_limits<double>::infinity();
  };

  /**
   * The gaps of every cell at the positions @p x (one Vector per cell, as
   * CellPopulation holds them), with a capillary wall of radius
   * @p wall_radius about the x axis if there is one, and in a segment
   * periodic with @p period along x, across its ends. The nearest points of
   * other cells come from one r-tree, not all pairs. Each rank of @p owners
   * measures from its own cells' points, searching only the cells that may
   * hold their nearest points (CellBoxes::nearest_candidates()); the ranks
   * then take the smallest of each gap in one reduction, so that every rank
   * gets every cell's. Collective on @p owners.
   */
  std::vector<CellGaps>
  measure_gaps(const std::vector<std::shared_ptr<Membrane>> &membranes,
               const std::vector<Vector<double>>            &x,
               const std::optional<double>                   wall_radius,
               const std::optional<double> period = std::nullopt,
               const CellOwners           &owners = CellOwners());
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_coupling_cell_boxes_h
#define rbc_ifem_coupling_cell_boxes_h

#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <optional>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The bounding box of every cell's membrane points, each point wrapped
   * into the segment of a periodic capillary: what decides which other
   * cells a rank must look at for its own cells' contact and gaps, before
   * any point is. Distances between two boxes are taken over the images
   * one period before and after as well, so that cells meet across the
   * ends. One pass over the points, then O(1) per pair of cells.
   */
  class CellBoxes
  {
  public:
    /// The boxes at the positions @p x (one Vector per cell), in a segment
    /// of length @p period along x if there is one.
    CellBoxes(const std::vector<std::shared_ptr<Membrane>> &membranes,
              const std::vector<Vector<double>>            &x,
              const std::optional<double>                  &period);

    /// The smallest distance between a point of cell @p a's box and one of
    /// cell @p b's or its images [µm]: no two of their points are closer.
    double
    distance(const unsigned int a, const unsigned int b) const;

    /**
     * The cells that come within @p range of a cell @p owners say this rank
     * owns (those included): every point of another cell within @p range
     * of an owned cell's point belongs to one of them. The ghosts a rank
     * needs for its cells' contact.
     */
    std::vector<bool>
    near_owned(const CellOwners &owners, const double range) const;

    /**
     * The cells that may hold the nearest point of another cell to a point
     * of a cell this rank owns (those included): a cell is left out when
     * its box is farther from the owned cell's than all of some other
     * cell's box is. What a nearest-point search (measure_gaps()) needs.
     */
    std::vector<bool>
    nearest_candidates(const CellOwners &owners) const;

  private:
    /// The largest distance between a point of @p a's box and one of
    /// @p b's, on the image of @p b that makes it smallest [µm].
    double
    farthest(const unsigned int a, const unsigned int b) const;

    /**
     * The smallest, over @p b's images, of the length whose components are
     * @p length(a_low, a_high, b_low, b_high) of the two boxes' extents
     * along each axis [µm].
     */
    template <typename AxisLength>
    double
    over_images(const unsigned int a,
                const unsigned int b,
                const AxisLength  &length) const;

    /// The shifts along x to @p b's images: 0 and, with a period, ±period.
    std::vector<double>
    shifts() const;

    std::vector<BoundingBox<3>> boxes;
    const std::optional<double> period;
  };
} // namespace rbc_ifem

#endif

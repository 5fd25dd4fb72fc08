#ifndef rbc_ifem_geometry_cell_layout_h
#define rbc_ifem_geometry_cell_layout_h

#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/geometry/evans_fung.h>
#include <rbc_ifem/geometry/parameters.h>

#include <vector>

namespace rbc_ifem
{
  /**
   * Where the red cells sit in the capillary segment: uniform, random or
   * clustered along the axis (x), every cell on the axis with the same
   * orientation. Needs no mesh and no solver, so experiments, tests and
   * users can build layouts directly.
   *
   * Every layout keeps the surfaces of neighbouring cells at least
   * Minimum gap apart and the cells at least half of it from the segment's
   * end faces, so that N cells fit if N (cell length + gap) <= length. The
   * cell length along the axis is the exact extent of the Evans-Fung shape
   * in its orientation (EvansFungShape::extent()).
   */
  class CellLayout
  {
  public:
    /**
     * Build the layout, or throw InputError naming the parameter if it is
     * impossible: a cell as wide as the capillary, more cells than fit, or
     * a cluster placed partly outside the segment.
     */
    CellLayout(const LayoutParameters   &layout,
               const GeometryParameters &geometry,
               const CellParameters     &cells);

    const std::vector<CellPlacement> &
    placements() const;

    /// The parameters the layout was built from.
    const LayoutParameters &
    parameters() const;

    /// Extent of one cell along the capillary axis [µm].
    double
    cell_length() const;

    /// The largest number of cells that fits with the given gap.
    unsigned int
    max_cells() const;

    /// Tube hematocrit: total cell volume / lumen volume π R² L.
    double
    hematocrit(const std::vector<double> &cell_volumes) const;

  private:
    void
    place_uniform();
    void
    place_random();
    void
    place_clustered();

    /// Append a cell centred on the axis at x.
    void
    add_cell_at(const double x);

    const LayoutParameters     layout;
    const GeometryParameters   geometry;
    const Tensor<1, 3>         axis;
    double                     length_of_cell;
    std::vector<CellPlacement> cells;
  };
} // namespace rbc_ifem

#endif

#include <rbc_ifem/geometry/placed_cells.h>

namespace rbc_ifem
{
  PlacedCells::PlacedCells(const CellLayout         &layout,
                           const GeometryParameters &geometry,
                           const CellParameters     &cells,
                           const unsigned int        surface_refinements)
    : layout(layout)
    , membranes(layout.placements(),
                EvansFungShape::of(cells),
                surface_refinements)
    , clearance(membranes.require_clearance(geometry.capillary_radius))
  {}

  PlacedCells::PlacedCells(const LayoutParameters   &layout,
                           const GeometryParameters &geometry,
                           const CellParameters     &cells,
                           const unsigned int        surface_refinements)
    : PlacedCells(CellLayout(layout, geometry, cells),
                  geometry,
                  cells,
                  surface_refinements)
  {}

  double
  PlacedCells::hematocrit() const
  {
    return layout.hematocrit(membranes.volumes());
  }
} // namespace rbc_ifem

#ifndef rbc_ifem_geometry_placed_cells_h
#define rbc_ifem_geometry_placed_cells_h

#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_membranes.h>
#include <rbc_ifem/geometry/cell_surface.h>

namespace rbc_ifem
{
  /**
   * The cells of one layout in the capillary, ready for a solver: the
   * CellLayout (InputError if it is impossible) and the membranes on it,
   * their meshes checked for clearance (InputError, naming Cells/Surface
   * refinements, if they cross each other or the wall).
   */
  struct PlacedCells
  {
    /// The cells of @p cells in @p layout, meshed with
    /// @p surface_refinements refinements, in the capillary of @p geometry.
    PlacedCells(const CellLayout         &layout,
                const GeometryParameters &geometry,
                const CellParameters     &cells,
                const unsigned int        surface_refinements);

    /// The same for the layout CellLayout(@p layout, @p geometry, @p cells).
    PlacedCells(const LayoutParameters   &layout,
                const GeometryParameters &geometry,
                const CellParameters     &cells,
                const unsigned int        surface_refinements);

    /// The tube hematocrit of the membranes.
    double
    hematocrit() const;

    const CellLayout    layout;
    const CellMembranes membranes;
    const Clearance     clearance;
  };
} // namespace rbc_ifem

#endif

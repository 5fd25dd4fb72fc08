#ifndef rbc_ifem_geometry_cell_membranes_h
#define rbc_ifem_geometry_cell_membranes_h

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_surface.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>

#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <vector>

namespace rbc_ifem
{
  /**
   * The membrane meshes of every cell of a layout, in their reference
   * shape (the Evans-Fung cell, or a sphere), with the MappingQ2 that curves
   * them and their measured area, volume and centroid.
   */
  class CellMembranes
  {
  public:
    CellMembranes(const std::vector<CellPlacement> &placements,
                  const EvansFungShape             &shape,
                  const unsigned int                surface_refinements);

    unsigned int
    size() const;

    /// The surfaces, for functions that take several.
    std::vector<const Triangulation<2, 3> *>
    surfaces() const;

    const MappingQ<2, 3> &
    mapping() const;

    /// The surfaces and their mapping, as the uptake solve takes them.
    MembraneSurfaces
    membrane_surfaces() const;

    const std::vector<SurfaceMeasures> &
    measures() const;

    std::vector<double>
    volumes() const;

    /// Every membrane vertex: where volume meshes are refined.
    std::vector<Point<3>>
    vertices() const;

    /// The table of cells.csv: cell,x,y,z,area,volume (centroid, µm, µm², µm³).
    CsvTable
    table() const;

    /**
     * Measure the gaps between membranes and to the capillary wall, and
     * throw InputError (naming Cells/Surface refinements) if the meshed
     * surfaces cross each other or the wall.
     */
    Clearance
    require_clearance(const double capillary_radius) const;

  private:
    const unsigned int                                surface_refinements;
    const MappingQ<2, 3>                              membrane_mapping;
    std::vector<std::unique_ptr<Triangulation<2, 3>>> membranes;
    std::vector<SurfaceMeasures>                      membrane_measures;
  };
} // namespace rbc_ifem

#endif

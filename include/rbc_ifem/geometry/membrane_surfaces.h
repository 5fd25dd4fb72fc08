#ifndef rbc_ifem_geometry_membrane_surfaces_h
#define rbc_ifem_geometry_membrane_surfaces_h

#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The red cells' membranes as the CO uptake solve sees them: a surface
   * mesh per cell and the mapping that curves them. Both the rigid cells of
   * a layout (CellMembranes::membrane_surfaces(): the reference shapes) and
   * the flowing ones (CellPopulation::membrane_surfaces(): the current
   * shapes) give this one view, so that the uptake solve takes one
   * argument, whoever owns the meshes.
   *
   * A view is cheap to copy. It may keep alive what it shows (@p owner):
   * the current shapes of flowing cells are built for the view and live as
   * long as any copy of it.
   */
  class MembraneSurfaces
  {
  public:
    /**
     * The meshes @p surfaces curved by @p mapping; @p owner, if given,
     * holds them and is kept alive by the view.
     */
    MembraneSurfaces(std::vector<const Triangulation<2, 3> *> surfaces,
                     const MappingQ<2, 3>                    &mapping,
                     std::shared_ptr<const void>              owner = {});

    /// The number of membranes (red cells).
    unsigned int
    size() const;

    /// The surface meshes, in the order of the cells.
    const std::vector<const Triangulation<2, 3> *> &
    meshes() const;

    /// The mapping that curves every surface mesh.
    const MappingQ<2, 3> &
    mapping() const;

    /// Every vertex of every surface mesh: where volume meshes are refined.
    std::vector<Point<3>>
    vertices() const;

  private:
    std::vector<const Triangulation<2, 3> *> surfaces;
    const MappingQ<2, 3>                    *surface_mapping;
    std::shared_ptr<const void>              owner;
  };

  // The functions, inline: they are small.
  inline MembraneSurfaces::MembraneSurfaces(
    std::vector<const Triangulation<2, 3> *> surfaces,
    const MappingQ<2, 3>                    &mapping,
    std::shared_ptr<const void>              owner)
    : surfaces(std::move(surfaces))
    , surface_mapping(&mapping)
    , owner(std::move(owner))
  {}

  inline unsigned int
  MembraneSurfaces::size() const
  {
    return surfaces.size();
  }

  inline const std::vector<const Triangulation<2, 3> *> &
  MembraneSurfaces::meshes() const
  {
    return surfaces;
  }

  inline const MappingQ<2, 3> &
  MembraneSurfaces::mapping() const
  {
    return *surface_mapping;
  }

  inline std::vector<Point<3>>
  MembraneSurfaces::vertices() const
  {
    std::vector<Point<3>> points;
    for (const Triangulation<2, 3> *surface : surfaces)
      points.insert(points.end(),
                    surface->get_vertices().begin(),
                    surface->get_vertices().end());
    return points;
  }
} // namespace rbc_ifem

#endif

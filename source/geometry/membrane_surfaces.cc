#include <rbc_ifem/geometry/membrane_surfaces.h>

namespace rbc_ifem
{
  MembraneSurfaces::MembraneSurfaces(
    std::vector<const Triangulation<2, 3> *> surfaces,
    const MappingQ<2, 3>                    &mapping,
    std::shared_ptr<const void>              owner)
    : surfaces(std::move(surfaces))
    , surface_mapping(&mapping)
    , owner(std::move(owner))
  {}

  unsigned int
  MembraneSurfaces::size() const
  {
    return surfaces.size();
  }

  const std::vector<const Triangulation<2, 3> *> &
  MembraneSurfaces::meshes() const
  {
    return surfaces;
  }

  const MappingQ<2, 3> &
  MembraneSurfaces::mapping() const
  {
    return *surface_mapping;
  }

  std::vector<Point<3>>
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

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/geometry/cell_membranes.h>


namespace rbc_ifem
{
  CellMembranes::CellMembranes(const std::vector<CellPlacement> &placements,
                               const EvansFungShape             &shape,
                               const unsigned int surface_refinements)
    : surface_refinements(surface_refinements)
    , membrane_mapping(2)
  {
    for (const CellPlacement &placement : placements)
      {
        membranes.push_back(std::make_unique<Triangulation<2, 3>>());
        create_cell_surface(*membranes.back(),
                            shape,
                            placement,
                            surface_refinements);
        membrane_measures.push_back(
          measure_surface(*membranes.back(), membrane_mapping));
      }
  }

  unsigned int
  CellMembranes::size() const
  {
    return membranes.size();
  }

  std::vector<const Triangulation<2, 3> *>
  CellMembranes::surfaces() const
  {
    std::vector<const Triangulation<2, 3> *> pointers;
    for (const auto &membrane : membranes)
      pointers.push_back(membrane.get());
    return pointers;
  }

  const MappingQ<2, 3> &
  CellMembranes::mapping() const
  {
    return membrane_mapping;
  }

  MembraneSurfaces
  CellMembranes::membrane_surfaces() const
  {
    return MembraneSurfaces(surfaces(), membrane_mapping);
  }

  const std::vector<SurfaceMeasures> &
  CellMembranes::measures() const
  {
    return membrane_measures;
  }

  std::vector<double>
  CellMembranes::volumes() const
  {
    std::vector<double> volumes;
    for (const SurfaceMeasures &m : membrane_measures)
      volumes.push_back(m.volume);
    return volumes;
  }

  std::vector<Point<3>>
  CellMembranes::vertices() const
  {
    return membrane_surfaces().vertices();
  }

  CsvTable
  CellMembranes::table() const
  {
    CsvTable table("cell,x,y,z,area,volume");
    for (unsigned int i = 0; i < membrane_measures.size(); ++i)
      {
        const SurfaceMeasures &m = membrane_measures[i];
        table.add(
          i, m.centroid[0], m.centroid[1], m.centroid[2], m.area, m.volume);
      }
    return table;
  }

  Clearance
  CellMembranes::require_clearance(const double capillary_radius) const
  {
    const Clearance clearance =
      measure_clearance(surfaces(), membrane_mapping, capillary_radius);
    // The layout keeps the true surfaces apart; meshes too coarse to follow
    // them can still cross, which no solver would survive.
    if (clearance.min_cell_gap <= 0. || clearance.min_wall_gap <= 0.)
      throw InputError("Cells/Surface refinements",
                       std::to_string(surface_refinements),
                       "the meshed membranes of this layout cross each other "
                       "or the wall; refine them or widen Layout/Minimum gap.");
    return clearance;
  }
} // namespace rbc_ifem

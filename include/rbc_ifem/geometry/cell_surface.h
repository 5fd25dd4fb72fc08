#ifndef rbc_ifem_geometry_cell_surface_h
#define rbc_ifem_geometry_cell_surface_h

#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/geometry/evans_fung.h>

#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <limits>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Build the membrane mesh of one cell: the 6-cell quadrilateral mesh of
   * the unit sphere, mapped onto the Evans-Fung shape at @p placement, with
   * an EvansFungManifold (manifold id 0) attached, then refined
   * @p n_refinements times. The normals of the mesh point out of the cell.
   */
  void
  create_cell_surface(Triangulation<2, 3>  &surface,
                      const EvansFungShape &shape,
                      const CellPlacement  &placement,
                      const unsigned int    n_refinements);

  /// The integral measures of a closed surface mesh.
  struct SurfaceMeasures
  {
    double   area   = 0.;
    double   volume = 0.; ///< enclosed volume
    Point<3> centroid;    ///< centroid of the enclosed volume
    /// ∫ (x - centroid) ⊗ (x - centroid) dV over the enclosed volume [µm⁵]:
    /// V a_i²/5 on the axes of an ellipsoid with semi-axes a_i.
    Tensor<2, 3> second_moment;
  };

  /**
   * Area, enclosed volume and volume centroid of a closed, outward oriented
   * surface mesh, by the divergence theorem: V = 1/3 ∫ (x-c)·n dA,
   * ∫_V x_i dV = 1/2 ∫ x_i² n_i dA and ∫_V x_i x_j dV = 1/5 ∫ x_i x_j x·n dA,
   * on the given @p mapping.
   */
  SurfaceMeasures
  measure_surface(const Triangulation<2, 3> &surface,
                  const MappingQ<2, 3>      &mapping);

  /// The ellipse of a body's cut by the x-y plane, the shear plane.
  struct ShearPlaneEllipse
  {
    double taylor_deformation = 0.; ///< (L - B)/(L + B)
    double inclination = 0.; ///< of L's axis from x, in (-π/2, π/2] [rad]
  };

  /**
   * L and B, the largest and smallest semi-axes in the x-y plane of the
   * ellipsoid with a body's @p second_moment (SurfaceMeasures): an
   * ellipsoid's is V a_i²/5 on each axis, so the semi-axes in the plane
   * scale as the square roots of the eigenvalues of its x-y block.
   */
  ShearPlaneEllipse
  shear_plane_ellipse(const Tensor<2, 3> &second_moment);

  /// The distances that tell whether cells overlap or touch the wall.
  struct Clearance
  {
    double min_cell_gap = std::numeric_limits<double>::infinity(); ///< [µm]
    double min_wall_gap = std::numeric_limits<double>::infinity(); ///< [µm]
    std::pair<unsigned int, unsigned int> closest_cells{0, 0};     ///< indices
  };

  /**
   * Distances between the cell surfaces, and from them to the capillary
   * wall (the cylinder of @p capillary_radius around the x axis), measured
   * on the meshes themselves: point clouds of vertices and quadrature points
   * on each surface (with @p mapping), compared by nearest-neighbour search.
   * The result overestimates the true surface distance by at most the
   * sampling error, about (point spacing)² / (8 × radius of curvature).
   */
  Clearance
  measure_clearance(const std::vector<const Triangulation<2, 3> *> &surfaces,
                    const MappingQ<2, 3>                           &mapping,
                    const double capillary_radius);
} // namespace rbc_ifem

#endif

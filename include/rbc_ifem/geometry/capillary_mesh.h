#ifndef rbc_ifem_geometry_capillary_mesh_h
#define rbc_ifem_geometry_capillary_mesh_h

#include <rbc_ifem/geometry/mesh_zone.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/base/point.h>
#include <deal.II/base/types.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <optional>
#include <vector>

/**
 * The two volume meshes of the capillary segment, both along the x axis from
 * x = 0 to x = Capillary length, hexahedral, with exact cylindrical
 * manifolds on every circle so refinement stays on the true geometry:
 *
 * - the fluid mesh: the lumen, r < Capillary radius;
 * - the diffusion mesh: lumen, vessel wall and gas layer as conforming
 *   concentric regions, told apart by material id.
 *
 * The ids below are part of the program's interface: the solvers use them
 * for boundary conditions and coefficients, users see them in ParaView.
 */
namespace rbc_ifem
{
  using namespace dealii;

  namespace FluidBoundary
  {
    constexpr types::boundary_id wall   = 0; ///< r = Capillary radius
    constexpr types::boundary_id inlet  = 1; ///< x = 0
    constexpr types::boundary_id outlet = 2; ///< x = Capillary length
  }                                          // namespace FluidBoundary

  namespace DiffusionBoundary
  {
    constexpr types::boundary_id alveolar_surface = 0; ///< outer gas surface
    constexpr types::boundary_id inlet_end        = 1; ///< x = 0
    constexpr types::boundary_id outlet_end       = 2; ///< x = length
  } // namespace DiffusionBoundary

  /**
   * The faces where the local part of a fully distributed mesh ends
   * without a neighbour (create_capillary_mesh()): not a boundary of the
   * capillary, so no boundary condition acts there.
   */
  constexpr types::boundary_id partition_edge =
    numbers::internal_face_boundary_id - 1;

  namespace Material
  {
    constexpr types::material_id plasma      = 0; ///< the lumen
    constexpr types::material_id vessel_wall = 1;
    constexpr types::material_id gas         = 2;
  } // namespace Material

  /**
   * The lumen mesh for the fluid, globally refined as the parameters say
   * (band refinement around cells is separate: refine_near_points()).
   */
  void
  create_fluid_mesh(Triangulation<3>         &triangulation,
                    const GeometryParameters &geometry,
                    const unsigned int        n_global_refinements);

  /// The lumen + wall + gas mesh for CO diffusion, globally refined.
  void
  create_diffusion_mesh(Triangulation<3>         &triangulation,
                        const GeometryParameters &geometry,
                        const unsigned int        n_global_refinements);

  /**
   * Attach the manifolds of a capillary mesh (create_fluid_mesh(),
   * create_diffusion_mesh(): the cylinder, and the transfinite blend of the
   * lumen's core) to @p triangulation, whose coarse cells carry their
   * manifold ids.
   */
  void
  attach_capillary_manifolds(Triangulation<3> &triangulation);

  /**
   * Create @p triangulation from @p description, the description of a
   * capillary mesh (TriangulationDescription::Utilities), with the manifolds
   * its serial mesh had, so that its vertices are the serial mesh's. The
   * faces where its local part ends get the boundary id partition_edge.
   */
  void
  create_capillary_mesh(
    parallel::fullydistributed::Triangulation<3>      &triangulation,
    const TriangulationDescription::Description<3, 3> &description);

  /**
   * Match the end faces of a periodic segment, x = 0 and x = L (boundary
   * ids 1 and 2 in both the fluid's and the diffusion's numbering), as
   * neighbours of @p mesh: so that a distributed mesh's ghost layer reaches
   * across the ends, and a serial one's description for it does.
   */
  void
  add_end_periodicity(Triangulation<3> &mesh);

  /**
   * Refine the cells at either end face of @p mesh (periodic:
   * add_end_periodicity()) whose image at the other end is finer, until the
   * two ends are refined alike: then every active face of one end has one
   * active face of the other as its image, and periodicity can be imposed
   * DoF by DoF, each pair the same way on every rank
   * (make_end_periodicity_constraints()). Refinement by a band or by the
   * gaps between cells can leave the ends unlike, and with unlike ends the
   * constraints must run from the finer end to the coarser one, both ways
   * at once on a long enough face: a cycle that AffineConstraints::close()
   * does not leave.
   */
  void
  match_end_refinement(Triangulation<3> &mesh);

  /**
   * @p p moved along x by a multiple of @p period into [0, period): where a
   * point of a cell that crossed the end of a periodic segment lies in the
   * segment's meshes. Without a period, @p p itself.
   */
  Point<3>
  wrap_into_segment(const Point<3> &p, const std::optional<double> &period);

  /**
   * What a band around @p points must see in the segment: each point
   * wrapped into it and, with a period, its two images one period before
   * and after, so that a band refined around a cell at one end reaches
   * across to the other (refine_near_points()).
   */
  std::vector<Point<3>>
  points_in_segment(const std::vector<Point<3>> &points,
                    const std::optional<double> &period);

  /**
   * Refine, @p n_steps times, every active cell that comes closer than
   * @p band_width to one of @p points (e.g. points on the membranes). The
   * distance is taken from the cell centre, less half the cell diameter.
   * Deterministic, so every rank of a shared triangulation does the same.
   * Only the cells of @p zone (by default the whole mesh) are refined.
   */
  void
  refine_near_points(Triangulation<3>            &triangulation,
                     const std::vector<Point<3>> &points,
                     const double                 band_width,
                     const unsigned int           n_steps,
                     const MeshZone              &zone = MeshZone());
} // namespace rbc_ifem

#endif

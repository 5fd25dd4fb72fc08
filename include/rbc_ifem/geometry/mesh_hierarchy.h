#ifndef rbc_ifem_geometry_mesh_hierarchy_h
#define rbc_ifem_geometry_mesh_hierarchy_h

#include <rbc_ifem/geometry/mesh_zone.h>

#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/grid/tria.h>

#include <functional>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The meshes of a global-coarsening multigrid below @p fine (a serial or
   * parallel::shared mesh): each the next finer one with every cell
   * coarsened once where it can be, coarsest first, down to the coarse
   * mesh; @p fine itself is not in the list.
   *
   * What deal.II's
   * MGTransferGlobalCoarseningTools::create_geometric_coarsening_sequence()
   * makes, but without copying @p fine: deal.II 9.4 copies a
   * TransfiniteInterpolationManifold (the lumen's core) by initialising it
   * with the source mesh, which on a mesh that is not uniformly refined
   * (the band around the cells) writes past the end of an array, and the
   * copy could not be used anyway (the manifold works only on the mesh it
   * was initialised with). Each level is made instead from @p fine's
   * coarse cells with manifolds of its own, refined as @p fine is, then
   * coarsened: the same vertices and the same curved geometry.
   */
  std::vector<std::shared_ptr<const Triangulation<3>>>
  global_coarsening_sequence(const Triangulation<3> &fine);

  /**
   * Make @p fine the fully distributed mesh that @p coarse and @p refine
   * build, and return the meshes of its global-coarsening multigrid (as
   * global_coarsening_sequence(), coarsest first), fully distributed too.
   *
   * Every rank builds its own part, and no rank the whole mesh: @p coarse
   * makes the whole coarse mesh on a serial Triangulation<3> (with its
   * boundary ids and manifolds; the capillary's or the shear box's, and with
   * @p periodic its periodic ends, add_end_periodicity()), and @p refine
   * refines the cells of the rank's MeshZone only: the coarse cells of its
   * slab along x and those around it, as the whole mesh would be refined
   * there (MeshZone::refine_global(), refine_near_points() with the zone).
   * The rank owns the cells of its slab and takes the description of them
   * and their ghost layer from its part (deal.II's
   * create_description_from_triangulation() for that rank). Each coarser
   * level is the rank's part coarsened once more, in the same slabs, so
   * that the transfers between levels stay within a rank. The capillary's
   * manifolds are attached as create_capillary_mesh() does. With
   * @p weights, one per coarse cell (such as fine_cells_per_coarse_cell()),
   * the slabs hold about equal weights instead of equal numbers of coarse
   * cells (MeshZone), the same slabs on every level.
   */
  std::vector<std::shared_ptr<const Triangulation<3>>>
  create_distributed_mesh_hierarchy(
    parallel::fullydistributed::Triangulation<3>                    &fine,
    const std::function<void(Triangulation<3> &)>                   &coarse,
    const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
    const bool                                                       periodic,
    const std::vector<double> &weights = {});

  /**
   * Make @p mesh the fully distributed mesh that @p coarse and @p refine
   * build, every rank its own part, as create_distributed_mesh_hierarchy()
   * builds its finest mesh (and with its multigrid hierarchy of levels, for
   * solvers that coarsen on the mesh's own levels), without the coarser
   * meshes. With @p weights, one per coarse cell (such as
   * fine_cells_per_coarse_cell()), the slabs hold about equal weights
   * instead of equal numbers of coarse cells (MeshZone).
   */
  void
  create_distributed_mesh(
    parallel::fullydistributed::Triangulation<3>                    &mesh,
    const std::function<void(Triangulation<3> &)>                   &coarse,
    const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
    const bool                                                       periodic,
    const std::vector<double> &weights = {});

  /**
   * Per coarse cell of the mesh that @p coarse and @p refine build, the
   * number of active cells it is refined into, the same on every rank of
   * @p communicator: the weights that balance create_distributed_mesh()'s
   * slabs, so that a mesh refined around a few red cells in one part of
   * the capillary is shared evenly. Each rank refines only its slab of
   * equal numbers of coarse cells (MeshZone::slab_only(): about half of
   * what it builds for its part of the mesh) and counts its cells there;
   * one sum over the ranks of as many numbers as coarse cells. Next to a
   * slab's ends the count can differ from the whole mesh's, by what the
   * refinement's smoothing would have brought from across: a weight, not
   * a mesh.
   */
  std::vector<double>
  fine_cells_per_coarse_cell(
    const MPI_Comm                                 communicator,
    const std::function<void(Triangulation<3> &)> &coarse,
    const std::function<void(Triangulation<3> &, const MeshZone &)> &refine,
    const bool                                                       periodic);
} // namespace rbc_ifem

#endif

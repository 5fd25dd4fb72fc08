#ifndef rbc_ifem_geometry_mesh_hierarchy_h
#define rbc_ifem_geometry_mesh_hierarchy_h

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
   * Make @p fine the fully distributed mesh that @p make builds, and return
   * the meshes of its global-coarsening multigrid (as
   * global_coarsening_sequence(), coarsest first), fully distributed too.
   *
   * @p make builds the serial mesh on a Triangulation<3> of its own (the
   * capillary's or the shear box's, refined where it should be); only rank
   * 0 calls it, so only rank 0 ever holds the whole mesh, while it
   * partitions it with METIS and sends every rank the description of its
   * cells and their ghost layer (deal.II's
   * create_description_from_triangulation_in_groups()). Each coarser level
   * is the serial mesh coarsened once more, described and sent the same
   * way. The capillary's manifolds are attached as create_capillary_mesh()
   * does; with @p periodic the end faces are periodic neighbours
   * (add_end_periodicity(), which @p make must apply to the serial mesh
   * too).
   */
  std::vector<std::shared_ptr<const Triangulation<3>>>
  create_distributed_mesh_hierarchy(
    parallel::fullydistributed::Triangulation<3>  &fine,
    const std::function<void(Triangulation<3> &)> &make,
    const bool                                     periodic);
} // namespace rbc_ifem

#endif

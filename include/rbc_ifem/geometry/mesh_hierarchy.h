#ifndef rbc_ifem_geometry_mesh_hierarchy_h
#define rbc_ifem_geometry_mesh_hierarchy_h

#include <deal.II/grid/tria.h>

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
} // namespace rbc_ifem

#endif

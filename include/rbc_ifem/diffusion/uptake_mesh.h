#ifndef rbc_ifem_diffusion_uptake_mesh_h
#define rbc_ifem_diffusion_uptake_mesh_h

#include <rbc_ifem/diffusion/parameters.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/grid/cell_id.h>

#include <functional>
#include <map>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The mesh of a CO uptake solve around a given set of membranes: the
   * capillary's diffusion mesh (Mesh/Diffusion global refinements), refined
   * Mesh/Diffusion band refinements times within Mesh/Band width of the
   * membranes' vertices, then where the cut cells' level set cannot resolve
   * the membranes (UnresolvedCutCells), each time built again.
   *
   * For cut cells the mesh is fully distributed: rank 0 builds the serial
   * mesh and sends each rank its cells and their ghost layer, partitioned by
   * METIS; a mesh built again keeps on each rank most of the cells it had
   * (partition_like()), so that the closest points a rank found on the last
   * attempt answer most of its questions on the next (MembraneDistance
   * remembers them). For the multiplier the mesh is shared: every rank
   * locates every membrane point in it.
   */
  class UptakeMesh
  {
  public:
    UptakeMesh(const GeometryParameters &geometry,
               const MeshParameters     &mesh_parameters,
               const DiffusionMethod     method,
               const MPI_Comm            communicator,
               TimerOutput              &timer);

    /**
     * Build the mesh around @p surfaces and call @p set_up on it until it
     * resolves them: where @p set_up throws UnresolvedCutCells, the mesh is
     * built again with those cells and their neighbours refined, up to
     * Mesh/Diffusion gap refinements times. After the last, two membranes
     * in one mesh cell are an InputError (naming the cells), and a ridge is
     * left as the mesh resolves it: @p set_up is called once more with its
     * second argument (refine ridges) false.
     */
    void
    build(const MembraneSurfaces                              &surfaces,
          const std::function<void(const parallel::TriangulationBase<3> &,
                                   const bool refine_ridges)> &set_up);

    /// The mesh the last build() ended with.
    const parallel::TriangulationBase<3> &
    triangulation() const;

    /// The vertices of the mesh on all ranks, each counted once.
    types::global_vertex_index
    n_global_vertices() const;

  private:
    /// The subdomain of each active cell of a serial mesh.
    using Partition = std::map<CellId, types::subdomain_id>;

    /// The mesh around the membranes of the current build(), refined
    /// where each entry of @p refinements lists cells, in turn.
    void
    make_serial(Triangulation<3> &mesh) const;
    /// Build the mesh of the recipe anew (a parallel one of the method's
    /// kind).
    void
    make();
    /**
     * Partition @p serial into @p n_parts by METIS, numbering the parts so
     * that each keeps as many cells of the last partition as it can; then
     * remember the new one.
     */
    void
    partition_like(Triangulation<3> &serial, const unsigned int n_parts);

    const GeometryParameters                        geometry;
    const MeshParameters                            mesh_parameters;
    const DiffusionMethod                           method;
    const MPI_Comm                                  communicator;
    TimerOutput                                    &timer;
    std::vector<Point<3>>                           band_points;
    std::vector<std::vector<CellId>>                refinements;
    Partition                                       partition;
    std::unique_ptr<parallel::TriangulationBase<3>> mesh;
  };
} // namespace rbc_ifem

#endif

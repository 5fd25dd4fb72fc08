#ifndef rbc_ifem_diffusion_uptake_mesh_h
#define rbc_ifem_diffusion_uptake_mesh_h

#include <rbc_ifem/diffusion/cut_cell_geometry.h>
#include <rbc_ifem/diffusion/parameters.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>
#include <rbc_ifem/geometry/mesh_zone.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/grid/cell_id.h>

#include <functional>
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
   * For cut cells the mesh is fully distributed and built by all ranks, as
   * the fluid mesh is (create_distributed_mesh()): every rank makes the
   * coarse mesh and refines only its zone (MeshZone: its slab of coarse
   * cells along x and two coarse cells around it), and owns the cells of
   * its slab. The slabs hold about equal numbers of cells: on every
   * attempt the ranks count them first (fine_cells_per_coarse_cell()). A
   * mesh built again moves the slabs' ends only as far as the new
   * refinement shifts the weights, so that a rank holds mostly the same
   * part of the capillary on every attempt, and the closest points it
   * found on the last answer most of its questions on the next
   * (MembraneDistance remembers them). For the multiplier the mesh is
   * shared: every rank builds it whole and locates every membrane point in
   * it.
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
    /// The capillary's coarse diffusion mesh, with its periodic ends.
    void
    make_coarse(Triangulation<3> &coarse) const;
    /**
     * Refine the part @p zone of @p mesh for the current build(): globally,
     * in the band around the membranes, then where each entry of
     * refinements lists cells, in turn (the ends of a periodic segment
     * kept alike after each step).
     */
    void
    refine(Triangulation<3> &mesh, const MeshZone &zone) const;
    /// Build the mesh of the recipe anew (a parallel one of the method's
    /// kind).
    void
    make();

    const GeometryParameters                        geometry;
    const MeshParameters                            mesh_parameters;
    const DiffusionMethod                           method;
    const MPI_Comm                                  communicator;
    TimerOutput                                    &timer;
    std::vector<Point<3>>                           band_points;
    std::vector<std::vector<CellId>>                refinements;
    std::unique_ptr<parallel::TriangulationBase<3>> mesh;
  };

  /**
   * Build @p mesh around @p surfaces (UptakeMesh::build()) with a
   * CutCellGeometry of degree @p degree on every attempt, the membranes
   * sampled once (MembraneDistance) for all of them; with
   * @p separate_insides the geometry a problem inside the cells needs.
   * Returns the geometry of the mesh that resolves them.
   */
  std::unique_ptr<CutCellGeometry>
  build_cut_cell_geometry(UptakeMesh               &mesh,
                          const GeometryParameters &geometry,
                          const MembraneSurfaces   &surfaces,
                          const unsigned int        degree,
                          const bool                separate_insides,
                          TimerOutput              &timer);
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_geometry_mesh_zone_h
#define rbc_ifem_geometry_mesh_zone_h

#include <deal.II/grid/tria.h>

#include <optional>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The part of a mesh that one rank builds, when every rank builds its own
   * part of a mesh along x (create_distributed_mesh_hierarchy()): the coarse
   * cells are given to the ranks in slabs along x, every rank alike from the
   * same coarse mesh (sorted by their centres' x, ties by index; rank r the
   * positions r C/P to (r+1) C/P - 1 of the C cells), and a rank refines
   * only the coarse cells of its zone: its slab and every coarse cell that
   * comes within two coarse cells' length of it (across the end of a
   * periodic segment too). The zone holds the rank's cells and their ghost
   * layer with room to spare, so that they are refined as in the whole
   * mesh: a cell's refinement depends only on what is near it (the band
   * around the membrane points, and the smoothing that keeps neighbours
   * within a level of each other, which spreads less than a coarse cell).
   *
   * The default zone is the whole mesh on one rank.
   */
  class MeshZone
  {
  public:
    /// The whole mesh, owned by rank 0.
    MeshZone() = default;

    /**
     * Rank @p rank's zone of @p n_ranks in the coarse mesh @p coarse (not
     * yet refined); with a @p period along x, the slabs at the two ends are
     * neighbours. With @p weights (one per coarse cell, such as the number
     * of cells it is refined into), the slabs are runs of about equal
     * weight instead of equal numbers of coarse cells, unless a cell
     * heavier than a rank's share would leave a rank without one.
     */
    MeshZone(const Triangulation<3>      &coarse,
             const unsigned int           rank,
             const unsigned int           n_ranks,
             const std::optional<double> &period,
             const std::vector<double>   &weights = {});

    /// Whether @p cell (of any level) lies in the zone: its coarse cell does.
    bool
    contains(const Triangulation<3>::cell_iterator &cell) const;

    /// The rank whose slab holds @p cell's coarse cell.
    unsigned int
    owner(const Triangulation<3>::cell_iterator &cell) const;

    /// Refine every active cell of the zone @p times times (of the whole
    /// mesh: Triangulation::refine_global()).
    void
    refine_global(Triangulation<3> &mesh, const unsigned int times) const;

    /// The same slabs, with a zone of the rank's slab alone (no coarse
    /// cells around it).
    MeshZone
    slab_only() const;
    /// Set every cell's subdomain and level subdomain id to its owner(),
    /// the partition a rank's description is taken from.
    void
    mark_owners(Triangulation<3> &mesh) const;

  private:
    /// Per coarse cell: the owner rank, and whether it is in the zone;
    /// empty for the whole mesh.
    std::vector<unsigned int> slab_of;
    unsigned int              rank = 0;
    std::vector<bool>         in_zone;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_diffusion_cut_cell_geometry_h
#define rbc_ifem_diffusion_cut_cell_geometry_h

#include <rbc_ifem/diffusion/membrane_distance.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>

#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q_cache.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/non_matching/fe_values.h>
#include <deal.II/non_matching/mesh_classifier.h>

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  /**
   * Cut cells of the diffusion mesh that the level set cannot resolve,
   * thrown by CutCellGeometry's constructor on every rank, with every such
   * cell, so that the caller can refine them and try again:
   * - two membranes pass through one cell: the gap between them is
   *   narrower than the mesh, and the level set cannot tell them apart
   *   (membranes names two of them);
   * - the distance to a membrane has a ridge inside a cut cell, where two
   *   sides of the membrane are equally far (the cell reaches across a thin
   *   part of the red cell, the biconcave dimple or a parachute's fold): the
   *   polynomial level set smooths the ridge's kink and moves the membrane.
   *   (The ridges between two membranes, in the plasma, are left alone:
   *   refining every gap costs three times the DoFs of seven cells for a
   *   quarter of a percent of DM.)
   */
  class UnresolvedCutCells : public std::runtime_error
  {
  public:
    UnresolvedCutCells(
      std::vector<CellId>                                         cells,
      const std::optional<std::pair<unsigned int, unsigned int>> &membranes);

    /// The mesh cells, on every rank.
    const std::vector<CellId> cells;
    /// Two membranes (indices into the membranes) that share a cell, if
    /// any do.
    const std::optional<std::pair<unsigned int, unsigned int>> membranes;
  };

  /**
   * The membranes in a diffusion mesh as cut cells see them, built once per
   * mesh and shared by every problem solved on it (CutCellDiffusion for DM,
   * CutCellReaction for DL), as step-85 builds its level set once:
   * - the level set φ, the Q_k interpolant of minus the signed distance to
   *   the membranes (MembraneDistance), < 0 in the plasma (deal.II's
   *   "inside"), so that Γh = {φ = 0} is within O(h^(k+1)) of them;
   * - the classification of the cells (NonMatching::MeshClassifier) and the
   *   quadratures on cut cells (NonMatching::FEValues, Saye's algorithm);
   * - the mapping's support points of the cells this rank evaluates on,
   *   placed on the capillary's manifolds once (MappingQCache);
   * - the membrane each surface quadrature point belongs to (its closest
   *   point), which the flux is handed back to;
   * - with Options::separate_insides, the red cell each mesh cell reaches
   *   into, and a colour per red cell that neighbours do not share.
   *
   * Each rank works on the cells it owns and the ghost layer around them;
   * the mesh is shared or fully distributed.
   */
  class CutCellGeometry
  {
  public:
    /// Which cut cells the constructor reports as unresolved.
    struct Options
    {
      /**
       * Cut cells with a ridge of the distance (default true). The caller
       * switches it off after the last refinement it allows: the ridges are
       * then resolved as well as the mesh resolves them.
       */
      bool refine_ridges = true;
      /**
       * Tell the red cells' insides apart (default false; a problem inside
       * the cells needs it, CutCellReaction): a cut cell whose level set
       * nodes are closest to two membranes is then unresolved, as one that
       * two membranes pass through, and the insides are found and coloured.
       * The level set smooths the ridge of the distance between two
       * membranes in such a cell, and where they are closer than about two
       * cells the smoothed level set joins their insides across the gap:
       * seven cells at band refinements 1 then hold 17% more volume. The
       * plasma side barely notices (DM moves by 0.2%), the reaction inside
       * the cells does.
       */
      bool separate_insides = false;
    };

    /// What a surface quadrature point of a cut cell is on.
    using SurfacePoints = std::vector<MembraneDistance::ClosestPoint>;

    /**
     * The geometry of @p membranes in @p mesh, for Q_@p degree fields, the
     * distance taken from @p distance (built for the same membranes: a
     * caller that sets up several meshes around them samples them once, and
     * finds each closest point once); with a @p period along x the segment
     * is periodic. Throws InputError if a membrane reaches into the vessel
     * wall or cuts no cell, UnresolvedCutCells (on every rank) for the cells
     * that @p options asks to be refined. @p mesh, @p membranes and
     * @p distance must outlive this object.
     */
    CutCellGeometry(const parallel::TriangulationBase<3>   &mesh,
                    const MembraneSurfaces                 &membranes,
                    std::shared_ptr<const MembraneDistance> distance,
                    const unsigned int                      degree,
                    const std::optional<double>            &period,
                    const Options                          &options,
                    TimerOutput                            &timer);
    ~CutCellGeometry();

    CutCellGeometry(const CutCellGeometry &) = delete;
    CutCellGeometry &
    operator=(const CutCellGeometry &) = delete;

    const parallel::TriangulationBase<3> &
    mesh() const;

    const MembraneSurfaces &
    membranes() const;

    /// The polynomial degree k of the level set and of the fields.
    unsigned int
    degree() const;

    /// The period along x of a periodic segment.
    const std::optional<double> &
    period() const;

    /// The mapping of the volume mesh, its support points cached.
    const MappingQCache<3> &
    mapping() const;

    /// The level set's DoFs and values (on owned cells and ghosts).
    const DoFHandler<3> &
    level_set_dof_handler() const;
    const LinearAlgebra::distributed::Vector<double> &
    level_set() const;

    /// Where @p cell lies: in the plasma ("inside"), in a red cell or the
    /// wall's exterior ("outside"), or cut.
    NonMatching::LocationToLevelSet
    location(const Triangulation<3>::cell_iterator &cell) const;

    bool
    is_cut(const Triangulation<3>::cell_iterator &cell) const;

    /**
     * FEValues of @p fe_collection on the plasma part, the cells' part and
     * the membrane part of each cell, with the quadratures of Q_k.
     * @p fe_collection must outlive them.
     */
    std::unique_ptr<NonMatching::FEValues<3>>
    cut_cell_values(const hp::FECollection<3>            &fe_collection,
                    const NonMatching::RegionUpdateFlags &flags) const;

    /// The membrane of each surface quadrature point, by the active cell
    /// index of the owned cut cells.
    const std::map<unsigned int, SurfacePoints> &
    surface_points() const;

    /// With Options::separate_insides: the red cell (membrane index) that
    /// mesh cell @p cell of this rank or its ghost layer reaches into, or
    /// numbers::invalid_unsigned_int for one wholly in the plasma.
    unsigned int
    inside_of(const Triangulation<3>::cell_iterator &cell) const;

    /// With Options::separate_insides: the colour of membrane @p m; two
    /// red cells whose mesh cells touch (across the periodic ends too)
    /// differ.
    unsigned int
    colour(const unsigned int m) const;

    /// With Options::separate_insides: the number of colours.
    unsigned int
    n_colours() const;

  private:
    /// Cut cells of this rank that two membranes pass through, and two such
    /// membranes (equal if there are none).
    struct SharedCells
    {
      std::vector<CellId>                   cells;
      std::pair<unsigned int, unsigned int> membranes{0, 0};
    };

    void
    cache_mapping();
    void
    compute_level_set();
    /// A level set node, where it is, and whether a cell of the lumen
    /// (Material::plasma) holds it.
    struct LevelSetNode
    {
      types::global_dof_index dof;
      Point<3>                position;
      bool                    in_lumen;
    };
    /**
     * The level set nodes of the cells this rank owns, each placed by the
     * cell with the smallest CellId that holds it (the cells' mappings
     * differ in the last digits), so that the ranks that share a node, and
     * any number of ranks, place it alike. Every cell that holds such a
     * node is owned or a ghost here, so the ranks agree on in_lumen too.
     */
    std::vector<LevelSetNode>
    level_set_nodes() const;
    /// Whether @p cell is cut and in the lumen (Material::plasma).
    bool
    is_cut_in_lumen(const Triangulation<3>::cell_iterator &cell) const;
    /// The cut cells of this rank that the distance has a ridge in: two of
    /// their level set nodes whose closest points on one membrane face
    /// opposite ways.
    std::vector<CellId>
    ridge_cells() const;
    /**
     * Find each surface quadrature point's membrane, and the cut cells that
     * two membranes share. Throws InputError if a membrane reaches into
     * the vessel wall or cuts no cell.
     */
    SharedCells
    locate_surface_points();
    /// Add to @p shared the cut cells of this rank whose level set nodes
    /// are closest to two membranes.
    void
    add_gap_cells(SharedCells &shared) const;
    /// Throw UnresolvedCutCells, on every rank, if any rank found
    /// @p ridges or @p shared cells.
    void
    throw_if_unresolved(const std::vector<CellId> &ridges,
                        const SharedCells         &shared) const;
    /// The red cell each mesh cell of this rank and its ghost layer
    /// reaches into (cell_membrane).
    void
    find_insides();
    /// Colour the membranes so that two whose mesh cells touch differ.
    void
    colour_membranes();

    const parallel::TriangulationBase<3>   *triangulation;
    const MembraneSurfaces                  surfaces;
    std::shared_ptr<const MembraneDistance> distance;
    const unsigned int                      k;
    const std::optional<double>             segment_period;
    const MPI_Comm                          communicator;
    TimerOutput                            &timer;

    MappingQCache<3>         cached_mapping;
    hp::MappingCollection<3> mapping_collection;
    /// On uncut cells, and the 1-D rule of the cut cells' quadratures.
    const hp::QCollection<3> cell_quadrature;
    const hp::QCollection<1> line_quadrature;
    const FE_Q<3>            level_set_fe;
    DoFHandler<3>            level_set_dofs;
    /// φ = −(signed distance): < 0 in the plasma (deal.II's "inside"), on
    /// the nodes of the cells this rank owns and their ghost neighbours.
    LinearAlgebra::distributed::Vector<double> level_set_values;
    /// The membrane closest to each level set node in the lumen of the
    /// cells this rank owns, and the outward normal at the closest point.
    std::map<types::global_dof_index, MembraneDistance::ClosestPoint>
                                                    closest_points;
    std::unique_ptr<NonMatching::MeshClassifier<3>> classifier;
    std::map<unsigned int, SurfacePoints>           points;
    /// With separate insides: the membrane each active mesh cell reaches
    /// into (by active cell index; invalid for the plasma's), and each
    /// membrane's colour.
    std::vector<unsigned int> cell_membrane, membrane_colour;
    unsigned int              colours = 0;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_coupling_cell_population_h
#define rbc_ifem_coupling_cell_population_h

#include <rbc_ifem/coupling/cell_force.h>
#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/geometry/evans_fung.h>
#include <rbc_ifem/geometry/membrane_surfaces.h>
#include <rbc_ifem/geometry/parameters.h>
#include <rbc_ifem/membrane/membrane.h>
#include <rbc_ifem/membrane/parameters.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// Size and shape of one deformed cell, the columns of cells.csv.
  struct CellShape
  {
    Point<3> centroid;          ///< of the enclosed volume [µm]
    double   area         = 0.; ///< [µm²]
    double   volume       = 0.; ///< [µm³]
    double   axial_length = 0.; ///< extent along the capillary axis x [µm]
    double   max_radius   = 0.; ///< largest distance from the x-parallel line
                                ///< through the centroid [µm]
    /// (L - 2r)/(L + 2r) with L the axial length and r the largest radius:
    /// -0.56 for the biconcave disc facing the flow, growing as it folds.
    double deformation_index = 0.;
    /// Taylor deformation (L - B)/(L + B) in the x-y plane, the shear plane
    /// of Experiment = shear (shear_plane_ellipse()).
    double taylor_deformation = 0.;
    /// Angle of L's axis from the x axis, in (-π/2, π/2] [rad].
    double inclination = 0.;
    /// max over the membrane's cells of |A/A0 - 1|: the local area change.
    double largest_local_area_change = 0.;
  };

  /**
   * The red cells of a flowing run: a Membrane per cell on its reference
   * (Evans-Fung) mesh, and each cell's current positions x. The membrane
   * points of the immersed coupling are the nodes of every cell, cell by
   * cell in Membrane::nodes() order; forces and velocities come and go in
   * that order. The forces on the points are the sum of the CellForce
   * objects the population holds.
   *
   * Every rank knows every cell's positions, but a rank keeps the reference
   * mesh and the Membrane only of the cells it owns: it makes them when it
   * takes a cell over and drops them when it hands the cell on. What it needs
   * of another cell depends on the reference shape alone, not on where the cell
   * was placed (the numbering of its nodes, its reference areas, its normals at
   * given positions), and it takes that from the first cell's Membrane, which
   * every rank keeps: the model of membranes().
   */
  class CellPopulation
  {
  public:
    /**
     * The cells at @p placements, their mechanics shared out over the ranks
     * of @p communicator, so that every rank must then compute the forces
     * and the stiffness together. With at least as many cells as ranks,
     * each cell has an owner rank (CellOwners) that computes its forces and
     * stiffness alone and keeps them and its Membrane; with fewer, every rank
     * keeps every cell and takes a share of every membrane's cell loops
     * (Membrane::share_work()). The owners go by where the cells are along the
     * capillary, in a periodic
     * segment of length @p period if there is one (each cell's mean point
     * wrapped into it), and are chosen again whenever the cells move. Each
     * rank makes every cell, one at a time, for its reference positions and
     * measures; with the cells shared out it keeps (makes again) its own
     * cells' only.
     */
    CellPopulation(const std::vector<CellPlacement> &placements,
                   const CellParameters             &cells,
                   const MembraneParameters         &membrane,
                   const MPI_Comm               communicator = MPI_COMM_SELF,
                   const std::optional<double> &period       = {});

    /// Not copied or moved: its cell forces refer to its membranes.
    CellPopulation(const CellPopulation &) = delete;
    CellPopulation &
    operator=(const CellPopulation &) = delete;

    /// Which rank owns which cell (with fewer cells than ranks every rank
    /// computes every cell, as on one rank).
    const CellOwners &
    owners() const;

    /// The rank of @p communicator that writes cell @p c's files: its owner,
    /// or with fewer cells than ranks, rank c.
    unsigned int
    writer(const unsigned int c, const MPI_Comm communicator) const;

    /// The ranks that write cells' files, writer(c) of some cell c, sorted.
    std::vector<unsigned int>
    writers(const MPI_Comm communicator) const;

    unsigned int
    size() const;
    unsigned int
    n_points() const;

    /// Every membrane point, cell by cell.
    std::vector<Point<3>>
    points() const;

    /**
     * Add @p force to the forces on the cells. The membranes' elasticity
     * (MembraneElasticity) is there from the start; a Tether, say, holds
     * the cells in place.
     */
    void
    add_force(std::unique_ptr<CellForce> force);

    /**
     * F = -∂E/∂x at every point [pN], the sum of every CellForce at the
     * current positions, summed over the ranks (every rank gets every
     * cell's; tests and small programs such as the examples use it, a
     * flowing run compute_owned_forces()); keeps them per cell for output
     * (last_forces()).
     */
    std::vector<Tensor<1, 3>>
    compute_forces();

    /**
     * compute_forces() in the rows of this rank's cells only (the others
     * zero), without the forces' sum over the ranks: a PointExchange takes
     * them to the points' fluid ranks (to_fluid_ranks()). The energy, the
     * held force and forces_finite() are summed over the ranks all the
     * same, in one reduction of five numbers (collective).
     */
    std::vector<Tensor<1, 3>>
    compute_owned_forces();

    /**
     * The forces of the last compute_forces() or compute_owned_forces(),
     * per cell in the order of its Membrane's DoFs [pN]: after
     * compute_owned_forces() those of the cells this rank owns (zero for
     * the others); a cell handed over since went with its forces, which its
     * new owner writes out (write_vtu()).
     */
    const std::vector<Vector<double>> &
    last_forces() const;

    /// Whether every force of the last compute_forces() or
    /// compute_owned_forces() is finite, the same on every rank.
    bool
    forces_finite() const;

    /**
     * Take the tangent stiffness K = ∂²E/∂x² of every CellForce at the
     * current positions, for stiffness_product() until the next call.
     */
    void
    linearize();

    /**
     * K δ at the positions of the last linearize(), with δ and K δ point by
     * point in the order of points() [pN]: the forces at x + δ are F - K δ
     * to first order.
     */
    std::vector<Tensor<1, 3>>
    stiffness_product(const std::vector<Tensor<1, 3>> &displacements) const;

    /// The diagonal of K at the positions of the last linearize(), point by
    /// point (its x, y and z entries).
    std::vector<Tensor<1, 3>>
    stiffness_diagonal() const;

    /**
     * stiffness_product() in the rows of this rank's cells only (the others
     * zero), without the sum over the ranks: it reads @p displacements at
     * points_read() only.
     */
    std::vector<Tensor<1, 3>>
    owned_stiffness_product(
      const std::vector<Tensor<1, 3>> &displacements) const;

    /// stiffness_diagonal() in the rows of this rank's cells only.
    std::vector<Tensor<1, 3>>
    owned_stiffness_diagonal() const;

    /**
     * The points whose displacements this rank's rows of K read, ascending:
     * those of its own cells and of the cells its contact pairs reach; with
     * the membranes shared (fewer cells than ranks), every point.
     */
    std::vector<unsigned int>
    points_read() const;

    /**
     * Per point, the rank whose rows of K hold it: its cell's owner; with
     * the membranes shared, where every rank holds every row, the point's
     * @p fluid_ranks entry (so that no value travels).
     */
    std::vector<unsigned int>
    point_owners(const std::vector<unsigned int> &fluid_ranks) const;

    /// Changes whenever linearize() takes K or the owners are chosen anew:
    /// what was built on points_read() and point_owners() is stale then.
    unsigned int
    stiffness_serial() const;

    /**
     * The net external force on the cells at the last compute_forces() or
     * compute_owned_forces() [pN]: what holds them
     * (CellForceReport::external_force, summed over the cells and ranks).
     */
    Tensor<1, 3>
    held_force() const;

    /// The energy of every CellForce at the last compute_forces() or
    /// compute_owned_forces(), over all ranks [pN µm].
    double
    energy() const;

    /**
     * Every cell's Membrane, in order: what cell forces act on. Entry c is
     * cell c's own where this rank owns c (every c on one rank, or with the
     * membranes shared); elsewhere it is the model, the first cell's: right
     * for the numbering, the reference areas and measures, and the normals
     * and areas at cell c's positions (all the same for every placement of
     * the shape, to rounding), wrong for what depends on where c was placed
     * (Membrane::reference_positions(), build_patches()).
     */
    const std::vector<std::shared_ptr<Membrane>> &
    membranes() const;

    /// Whether this rank keeps cell @p c's own Membrane (membranes()).
    bool
    holds(const unsigned int c) const;

    /// Move every point by Δt v, the last of the six steps, and choose the
    /// cells' owners anew (collective on a communicator); a stiffness
    /// taken before is gone.
    void
    move(const std::vector<Tensor<1, 3>> &velocities, const double time_step);

    /// The volume of every cell now [µm³], each measured by its owner and
    /// shared with every rank in one reduction (collective).
    std::vector<double>
    volumes() const;

    /// Size and shape of every cell now, each measured by its owner and
    /// shared with every rank in one reduction (collective).
    std::vector<CellShape>
    shapes() const;

    /**
     * The current surfaces, for the CO diffusion solve: copies of the
     * reference meshes with the current vertices (see
     * Membrane::build_surface), flat-sided between them.
     */
    std::vector<std::unique_ptr<Triangulation<2, 3>>>
    current_surfaces() const;

    /**
     * The current surfaces as the uptake solve sees them: the
     * current_surfaces(), curved by the reference shape plus the
     * displacement (DeformedSurfaceMapping); the view holds both.
     */
    MembraneSurfaces
    membrane_surfaces() const;

    /**
     * The largest distance between neighbouring membrane points (the
     * longest cell edge over the degree) in the reference shape [µm].
     */
    double
    point_spacing() const;

    /// The reference area and volume of cell @p c.
    double
    reference_area(const unsigned int c) const;
    double
    reference_volume(const unsigned int c) const;

    /**
     * Each cell as NAME_C_CCCC.vtu, with the displacement, the last forces
     * (`force`, pN per node) and the same per unit area (`force_density`,
     * pN/µm²), each file carrying @p field_data; returns every cell's file
     * name. Call it on every rank of @p communicator: cell c is written by
     * rank writer(c, @p communicator) alone.
     */
    std::vector<std::string>
    write_vtu(const std::string &directory,
              const std::string &name,
              const unsigned int counter,
              const FieldData   &field_data   = {},
              const MPI_Comm     communicator = MPI_COMM_SELF) const;

    /**
     * The same fields of every cell in one grouped file: each rank of
     * writers() its cells as the piece NAME_CCCC.RANK.vtu, with the cell
     * field `cell` (the cell's index), and the first of them the
     * NAME_CCCC.pvtu that joins the pieces, whose name it returns. Call it
     * on every rank; it waits for no other.
     */
    std::string
    write_grouped_vtu(const std::string &directory,
                      const std::string &name,
                      const unsigned int counter,
                      const FieldData   &field_data,
                      const MPI_Comm     communicator) const;

    /// The positions of every cell, for a checkpoint.
    const std::vector<Vector<double>> &
    positions() const;
    /// Set them, and choose the owners anew as move() does.
    void
    set_positions(const std::vector<Vector<double>> &positions);

  private:
    /**
     * Make cell @p c's reference mesh and Membrane (the model's numbering
     * shared) into @p mesh and return the Membrane: what the constructor does
     * for every cell, and a rank for a cell it takes over.
     */
    std::shared_ptr<Membrane>
    make_membrane(const unsigned int                    c,
                  std::unique_ptr<Triangulation<2, 3>> &mesh) const;

    /**
     * Give the cells to owners by where they are now (CellOwners::place()),
     * if they are shared out, and keep the Membranes of this rank's cells
     * (keep_own_membranes()); the stiffness, taken with the owners before,
     * is dropped when a cell changed owner.
     */
    void
    place_owners();

    /// Make the Membranes of the cells this rank owns and does not hold,
    /// drop those of the cells it holds and does not own (but the model).
    void
    keep_own_membranes();

    /// The output of cell @p c (write_vtu()) as the patches of @p data_out.
    void
    build_patches(const unsigned int c, DataOut<2, 3> &data_out) const;

    /// The shape of cell @p c, whose current @p surface is given.
    CellShape
    shape(const unsigned int c, const Triangulation<2, 3> &surface) const;

    /// Add every CellForce at the current positions into the forces of
    /// this rank's cells, and their energy and external force.
    void
    add_every_cell_force();

    /// This rank's energy, external force (x, y, z) and count of forces
    /// that are not finite in its cells, to be summed over the ranks; and
    /// the sums taken back.
    std::vector<double>
    owned_totals() const;
    void
    take_totals(const std::vector<double> &totals);

    /// One Vector per cell from values point by point, and back.
    std::vector<Vector<double>>
    per_cell(const std::vector<Tensor<1, 3>> &values) const;
    std::vector<Tensor<1, 3>>
    per_point(const std::vector<Vector<double>> &values) const;

    /// K @p displacements and K's diagonal in the rows of this rank's cells,
    /// one Vector per cell.
    std::vector<Vector<double>>
    owned_rows_product(const std::vector<Tensor<1, 3>> &displacements) const;
    std::vector<Vector<double>>
    owned_rows_diagonal() const;

    const std::vector<CellPlacement> placements;
    const EvansFungShape             shape_of_cells;
    const unsigned int               surface_refinements;
    const MembraneParameters         membrane_parameters;
    const MappingQ<2, 3>             flat_mapping;
    /// The reference meshes of the cells whose own Membrane this rank keeps
    /// (holds()), null for the others; declared before the membranes that
    /// refer to them.
    std::vector<std::unique_ptr<Triangulation<2, 3>>> reference_meshes;
    /// The first cell's Membrane, kept by every rank (membranes()).
    std::shared_ptr<Membrane>              model;
    std::vector<std::shared_ptr<Membrane>> cell_membranes;
    /// Every cell's reference area and volume [µm², µm³], and the largest
    /// point spacing of them all (point_spacing()), measured at the start.
    std::vector<double> areas0;
    std::vector<double> volumes0;
    double              largest_spacing = 0.;
    /// Declared before the forces, which hold it.
    CellOwners cell_owners;
    /// The period of the segment the owners are placed in.
    std::optional<double>                   period;
    std::vector<Vector<double>>             x;
    std::vector<Vector<double>>             forces;
    unsigned int                            n_membrane_points = 0;
    std::vector<std::unique_ptr<CellForce>> cell_forces;
    /// The stiffness of each of cell_forces at the last linearize().
    std::vector<std::unique_ptr<CellForceStiffness>> stiffnesses;
    unsigned int                                     n_stiffness_changes = 0;
    Tensor<1, 3>                                     external_force;
    double                                           total_energy      = 0.;
    bool                                             all_forces_finite = true;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_coupling_immersed_coupling_h
#define rbc_ifem_coupling_immersed_coupling_h

#include <rbc_ifem/fluid/fluid_vectors.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>

#include <optional>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The immersed coupling of membranes and plasma (doc/design.md, "Immersed
   * coupling", steps 3 and 5): the membrane points, every node of every
   * cell, located on the fluid mesh. Each point belongs to the rank whose
   * cell holds it, which knows the cell and the point's reference
   * position there; the mesh may be parallel::shared or fully distributed,
   * since a rank searches only its own cells.
   *
   * Both directions use the same values φ_J(x_I) of the fluid's velocity
   * shape functions at the points:
   *
   *   spreading      f_J = Σ_I F_I · φ_J(x_I),
   *   interpolation  v_I = Σ_J v_J φ_J(x_I),
   *
   * so they are adjoint, ⟨f, v⟩ = Σ_I F_I · v_I: the power the membranes
   * put into the fluid is the power the fluid does on them. Since the
   * velocity space holds the constants and (Q2) the linear functions,
   * spreading keeps the total force and the total torque.
   *
   * Every rank keeps the positions, forces and velocities of all points
   * (the same on every rank); a rank computes only with the points in its
   * own cells. interpolate() sums the velocities over the ranks; the
   * semi-implicit load instead sends each point's value to the ranks that
   * need it (evaluate(), PointExchange).
   */
  class ImmersedCoupling
  {
  public:
    /**
     * @p velocity_dof_handler is the fluid's velocity space. With a
     * @p period along x (a periodic segment), every point is placed where
     * it lies in the segment (wrap_into_segment()): a membrane stays whole
     * for its mechanics while its points are found, spread and
     * interpolated across the ends.
     */
    ImmersedCoupling(const Triangulation<3>      &triangulation,
                     const Mapping<3>            &mapping,
                     const DoFHandler<3>         &velocity_dof_handler,
                     const std::optional<double> &period = std::nullopt);

    /**
     * Place the points, at the start and after every move (the same list on
     * every rank). A point a rank held stays with it if it is still in the
     * same cell or one that shares a vertex with it (most points, most
     * steps: one inverse mapping each); the others are looked for by every
     * rank among its own cells (an R-tree of their bounding boxes). A point
     * on a face between two ranks' cells goes to the lower rank, so each
     * point is on exactly one rank. Throws std::runtime_error naming the
     * first point that lies outside the fluid domain, on every rank alike.
     */
    void
    place(const std::vector<Point<3>> &points);

    /**
     * Add f_J = Σ_I F_I · φ_J(x_I) to @p load (the layout of
     * FluidProblem::initialize_velocity_vector(), its ghost entries zero;
     * compressed here), condensed with @p constraints.
     */
    void
    spread(const std::vector<Tensor<1, 3>> &forces,
           const AffineConstraints<double> &constraints,
           VelocityVector                  &load) const;

    /**
     * Add f_J = Σ_I w_I · φ_J(x_I)² to @p load, as spread() adds its
     * forces: with w_I the diagonal of a stiffness K of the points, the
     * diagonal of Sᵀ K S if K had no entries between two points.
     */
    void
    spread_squares(const std::vector<Tensor<1, 3>> &weights,
                   const AffineConstraints<double> &constraints,
                   VelocityVector                  &load) const;

    /**
     * v_I = Σ_J v_J φ_J(x_I) at every point, from @p velocity (ghosted);
     * the same result on every rank.
     */
    std::vector<Tensor<1, 3>>
    interpolate(const VelocityVector &velocity) const;

    /**
     * v_I = Σ_J v_J φ_J(x_I) at this rank's points, from @p velocity
     * (ghosted), zero at the others: interpolate() without its sum over
     * the ranks, for a PointExchange to take where it is needed.
     */
    std::vector<Tensor<1, 3>>
    evaluate(const VelocityVector &velocity) const;

    /// Per point, the rank whose fluid cell holds it, the same on every
    /// rank (place()).
    const std::vector<unsigned int> &
    point_ranks() const;

    /// The fluid mesh's communicator.
    MPI_Comm
    get_communicator() const;

    /// How many times place() has placed the points: what was built on
    /// point_ranks() is stale when this changes.
    unsigned int
    n_placements() const;

    unsigned int
    n_points() const;

    /// The points in this rank's cells.
    unsigned int
    n_locally_owned_points() const;

    /// The indices of the points in this rank's cells, cell by cell.
    const std::vector<unsigned int> &
    locally_owned_point_indices() const;

    /**
     * The fluid mesh size the membranes see: the largest edge length
     * (shortest vertex distance) of the fluid cells that hold points [µm].
     * Collective.
     */
    double
    mesh_size_at_points() const;

  private:
    using CellIterator = Triangulation<3>::active_cell_iterator;

    /// spread() with the shape values to the power @p power (1 or 2).
    void
    spread_power(const std::vector<Tensor<1, 3>> &forces,
                 unsigned int                     power,
                 const AffineConstraints<double> &constraints,
                 VelocityVector                  &load) const;

    /**
     * The reference position of @p p in the locally owned @p cell, if it
     * lies there.
     */
    std::optional<Point<3>>
    reference_in(const CellIterator &cell, const Point<3> &p) const;

    /**
     * The cell of @p candidates that holds @p p: the one it is clearly
     * inside, or, for a point on a face or an edge, the one of lowest
     * index; none if no candidate holds it.
     */
    std::optional<std::pair<CellIterator, Point<3>>>
    choose(const std::vector<CellIterator> &candidates,
           const Point<3>                  &p) const;

    /// @p p clearly inside @p cell or a locally owned cell sharing a vertex
    /// with it; none for a point on their faces.
    std::optional<std::pair<CellIterator, Point<3>>>
    locate_near(const CellIterator &cell, const Point<3> &p) const;

    /// @p p in any locally owned cell.
    std::optional<std::pair<CellIterator, Point<3>>>
    locate_anywhere(const Point<3> &p) const;

    /**
     * Find the cells of the points @p wrapped (in the segment) on this
     * rank, into owner_cell and reference_points; returns per point the
     * lowest rank that found it, the same on every rank (or the largest
     * unsigned int if none did).
     */
    std::vector<unsigned int>
    claim_points(const std::vector<Point<3>> &wrapped);

    /// Sort this rank's points by their cells: points_by_cell,
    /// point_cells and cell_start.
    void
    group_points_by_cell();

    /// The velocity shape functions' values at this rank's points.
    void
    take_shape_values();

    /**
     * Call @p f(dofs, first, last) for every cell of this rank that holds
     * points, with the cell's DoF indices and the range of its points in
     * points_by_cell.
     */
    template <typename CellFunction>
    void
    for_each_point_cell(const CellFunction &f) const;

    const Triangulation<3>     &triangulation;
    const Mapping<3>           &mapping;
    const DoFHandler<3>        &dof_handler;
    const std::optional<double> period;
    const GridTools::Cache<3>   cache;
    unsigned int                n_membrane_points = 0;
    unsigned int                placements        = 0;
    /// Per point: the rank that holds it (claim_points()).
    std::vector<unsigned int> fluid_ranks;
    /// Per point: the locally owned cell that holds it, or end().
    std::vector<CellIterator> owner_cell;
    /// Per point: its reference position in owner_cell.
    std::vector<Point<3>> reference_points;
    /// The points of this rank grouped by cell: the cells, the start of
    /// each cell's points in points_by_cell (one more entry at the end).
    std::vector<CellIterator> point_cells;
    std::vector<unsigned int> cell_start;
    std::vector<unsigned int> points_by_cell;
    /// (local DoF k, velocity component c) of every velocity shape function.
    std::vector<std::pair<unsigned int, unsigned int>> velocity_shape_functions;
    /**
     * The velocity shape functions' values φ_k(x_I) at every point of
     * this rank, in the order of points_by_cell: taken in place(), used by
     * spread() and interpolate().
     */
    std::vector<double> shape_values;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_coupling_cell_owners_h
#define rbc_ifem_coupling_cell_owners_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Which rank owns which red cell: the one rank that computes the cell's
   * membrane mechanics (its forces and tangent stiffness,
   * MembraneElasticity) and writes its files. The owners are chosen by
   * where the cells are (place()): ranks take runs of the cells in their
   * order along the capillary, as even as N cells allow, so that a rank's
   * cells are neighbours and its contact search sees few cells of other
   * ranks (ghosts). As the cells flow the order changes (a cell crossing
   * the end of a periodic segment goes from the last run to the first)
   * and cells are handed over between steps. Every rank still holds every
   * cell's positions. A cell's forces (its elasticity, its contact with
   * cells near it and the forces that hold or push it, CellForce) stay
   * with its owner and go with the cell when it is handed over
   * (hand_over()); what every rank needs of every cell, such as the
   * volumes and shapes, is summed over the owners in one reduction for all
   * cells (add_up()). Issue 51 goes on to ghost copies near the owned cells
   * instead of every cell everywhere.
   */
  class CellOwners
  {
  public:
    /// The cells shared out over the ranks of @p communicator, cell c on
    /// rank c modulo the ranks until place(); with MPI_COMM_SELF (the
    /// default) this rank owns every cell.
    explicit CellOwners(const MPI_Comm communicator = MPI_COMM_SELF);

    /**
     * Give the ranks runs of the cells in the order of @p where (each
     * cell's position along the capillary [µm], the same on every rank),
     * rank r the positions r N/P to (r + 1) N/P - 1 of that order, ties by
     * cell number. Returns the cells this rank owned before and no longer
     * does. Checks, in one reduction of two numbers, that the ranks'
     * owned cells add up to N and their owned @p points (each cell's
     * number of points) to the total: no cell lost or doubled, or
     * std::runtime_error. Collective; nothing to do on one rank.
     */
    std::vector<unsigned int>
    place(const std::vector<double>       &where,
          const std::vector<unsigned int> &points);

    /// How many times a cell went to another rank in place(), since the
    /// first placement.
    unsigned int
    n_handovers() const;

    /// The rank that owns cell @p c.
    unsigned int
    owner(const unsigned int c) const;

    /// Whether this rank owns cell @p c.
    bool
    owns(const unsigned int c) const;

    /// Whether the cells are shared out over more than one rank.
    bool
    shared() const;

    /**
     * Replace @p values (one Vector per cell) and @p scalars on every rank
     * by their sums over the ranks, in one reduction: each rank gives its
     * own cells' values and zeros for the others, so that every rank gets
     * every cell's. Collective; nothing to do on one rank.
     */
    void
    add_up(std::vector<Vector<double>> &values,
           const ArrayView<double>     &scalars) const;

    /**
     * Send the @p values (one Vector per cell) of every cell that changed
     * owner in the last place() from its owner @p before (per cell, the
     * owners before that place()) to its new owner, point to point: what an
     * owner alone keeps of a cell goes with the cell. Every rank knows both
     * ends of every hand-over, so nothing is asked; call it on every rank.
     */
    void
    hand_over(const std::vector<unsigned int> &before,
              std::vector<Vector<double>>     &values) const;

    /// Replace @p values on every rank by their smallest over the ranks, in
    /// one reduction. Collective; nothing to do on one rank.
    void
    take_smallest(const ArrayView<double> &values) const;

  private:
    MPI_Comm     communicator;
    unsigned int rank;
    unsigned int n_ranks;
    /// The owner of each cell, from place(); empty before.
    std::vector<unsigned int> owner_of;
    unsigned int              handovers = 0;
    /// What add_up() packs and sends, kept so that a product inside every
    /// linear iteration allocates nothing.
    mutable std::vector<double> packed;
  };
} // namespace rbc_ifem

#endif

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
   * MembraneElasticity) and writes its files. Cell c belongs to rank c
   * modulo the ranks, which shares N cells out evenly. Every rank still
   * holds every cell's positions and gets every cell's results, summed
   * over the owners in one reduction for all cells (add_up()): its
   * elasticity, its contact with cells near it and the forces that hold or
   * push it (CellForce). Issue 51
   * goes on to owners chosen by where the cells are, with ghost copies
   * near them instead of every cell everywhere.
   */
  class CellOwners
  {
  public:
    /// The cells shared out over the ranks of @p communicator; with
    /// MPI_COMM_SELF (the default) this rank owns every cell.
    explicit CellOwners(const MPI_Comm communicator = MPI_COMM_SELF);

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

    /// Replace @p values on every rank by their smallest over the ranks, in
    /// one reduction. Collective; nothing to do on one rank.
    void
    take_smallest(const ArrayView<double> &values) const;

  private:
    MPI_Comm     communicator;
    unsigned int rank;
    unsigned int n_ranks;
    /// What add_up() packs and sends, kept so that a product inside every
    /// linear iteration allocates nothing.
    mutable std::vector<double> packed;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_geometry_cell_records_h
#define rbc_ifem_geometry_cell_records_h

#include <deal.II/base/array_view.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Values on active cells of a mesh, each cell's keyed by its CellId (the
   * coarse cell and the path of children to it), so that they mean the same
   * on any partition of the mesh: what a checkpoint stores of a field, to be
   * read on another number of ranks (doc/ifem.md, Section 5).
   *
   * Every cell has the same number of values. A rank adds the records of
   * its own cells; after the ranks have exchanged them (to_owners()), each
   * holds the records of the cells it owns on another partition of the
   * same mesh.
   */
  class CellRecords
  {
  public:
    /// No records, @p values_per_cell values each.
    explicit CellRecords(const unsigned int values_per_cell = 0);

    /// Add the record of @p cell: @p values, values_per_cell() of them.
    void
    add(const CellId &cell, const ArrayView<const double> &values);

    /// The number of records.
    unsigned int
    size() const;

    unsigned int
    values_per_cell() const;

    /// The cell of record @p i.
    CellId
    cell(const unsigned int i) const;

    /// The values of record @p i.
    ArrayView<const double>
    values(const unsigned int i) const;

    /// The records as bytes (a Boost binary archive) and back.
    std::string
    to_bytes() const;
    static CellRecords
    from_bytes(const std::string &bytes);

    /**
     * The records of the locally owned active cells of @p mesh, collected
     * from every rank's records (collective). A rank's records may be of
     * any cells of the mesh; each record goes, with the others of its coarse
     * cell, to a home rank (the coarse cell's index modulo the ranks), which
     * hands it to the cell's owner: two exchanges with the ranks that have
     * something to say, and nothing on any rank that grows with the mesh
     * beyond its share. Throws std::runtime_error on every rank, naming one
     * of them, if a locally owned cell has no record; records of cells the
     * mesh does not have are left.
     */
    CellRecords
    to_owners(const Triangulation<3> &mesh) const;

    /// For Boost serialization (defined in the .cc, which alone uses it).
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int version);

  private:
    unsigned int                     n_values;
    std::vector<CellId::binary_type> cells;
    std::vector<double>              data; ///< n_values per cell
  };
} // namespace rbc_ifem

#endif

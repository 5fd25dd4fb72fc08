#ifndef rbc_ifem_geometry_cell_layout_h
#define rbc_ifem_geometry_cell_layout_h

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/geometry/evans_fung.h>
#include <rbc_ifem/geometry/parameters.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  /**
   * Where the red cells sit in the capillary segment: uniform, random or
   * clustered along the axis (x), every cell on the axis with the same
   * orientation; or each cell where a file puts it (Layout/Kind = file).
   * Needs no mesh and no solver, so experiments, tests and users can build
   * layouts directly.
   *
   * Every layout keeps the surfaces of neighbouring cells at least
   * Minimum gap apart and the cells at least half of it from the segment's
   * end faces, so that N cells fit if N (cell length + gap) <= length. The
   * cell length along the axis is the exact extent of the Evans-Fung shape
   * in its orientation (EvansFungShape::extent()). The built-in kinds keep
   * the gaps by construction; a file's cells are checked against the exact
   * shape (check_file_cells()).
   */
  class CellLayout
  {
  public:
    /**
     * Build the layout, or throw InputError naming the parameter if it is
     * impossible: a cell as wide as the capillary, more cells than fit, a
     * cluster placed partly outside the segment, or a Layout/File that
     * cannot be read or whose cells overlap, leave the segment or reach
     * the wall (the message names the file, the line and the cell).
     */
    CellLayout(const LayoutParameters   &layout,
               const GeometryParameters &geometry,
               const CellParameters     &cells);

    const std::vector<CellPlacement> &
    placements() const;

    /// The parameters the layout was built from.
    const LayoutParameters &
    parameters() const;

    /// "uniform, 3 cells, seed 1" (or "file F, 3 cells"), for the log.
    std::string
    description() const;

    /// layout_<kind>_<n>_<seed>.csv: where the layouts experiments write it.
    std::string
    file_name() const;

    /// The cells as Layout/File reads them: x,y,z,axis_x,axis_y,axis_z.
    CsvTable
    table() const;

    /// Extent of one cell along the capillary axis [µm].
    double
    cell_length() const;

    /// The largest number of cells that fits with the given gap.
    unsigned int
    max_cells() const;

    /// Tube hematocrit: total cell volume / lumen volume π R² L.
    double
    hematocrit(const std::vector<double> &cell_volumes) const;

  private:
    void
    place_uniform();
    void
    place_random();
    void
    place_clustered();
    /// The cells of Layout/File, checked.
    void
    place_from_file(const EvansFungShape &shape);
    /**
     * Throw InputError, naming Layout/File, the line and the cell, unless
     * every cell lies in the segment (check_file_cell_in_segment()) and
     * keeps Minimum gap from every other cell, in a periodic segment from
     * its nearest image across the ends. The gap is measured between dense
     * samples of the exact surfaces (its error is below 0.01 µm), and a
     * sample of one cell inside another is an overlap whatever the
     * sampling.
     */
    void
    check_file_cells(const EvansFungShape            &shape,
                     const std::vector<unsigned int> &lines) const;

    /**
     * Throw InputError naming @p cell_text unless @p cell lies inside the
     * lumen (its exact distance from the axis) and, in a closed segment,
     * keeps half of Minimum gap from the end faces (its exact extent); in a
     * periodic one (Geometry/Periodic) it may reach across an end, its
     * centre in [0, L) and its length with Minimum gap under L.
     */
    void
    check_file_cell_in_segment(const EvansFungShape &shape,
                               const std::string    &cell_text,
                               const CellPlacement  &cell) const;

    /// Append a cell centred on the axis at x.
    void
    add_cell_at(const double x);

    const LayoutParameters     layout;
    const GeometryParameters   geometry;
    const Tensor<1, 3>         axis;
    double                     length_of_cell;
    std::vector<CellPlacement> cells;
  };

  /**
   * The layout @p layout of a study (subsection Layout study), or an
   * InputError that names Layout study/Numbers of cells and says why.
   */
  CellLayout
  study_layout(const LayoutParameters   &layout,
               const GeometryParameters &geometry,
               const CellParameters     &cells);
} // namespace rbc_ifem

#endif

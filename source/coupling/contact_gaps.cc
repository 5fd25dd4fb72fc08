#include <rbc_ifem/coupling/cell_boxes.h>
#include <rbc_ifem/coupling/contact_gaps.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <cmath>

namespace rbc_ifem
{
  namespace
  {
    /// Every rank's gaps, the smallest of each over the ranks, in one
    /// reduction.
    void
    take_smallest(std::vector<CellGaps> &gaps, const CellOwners &owners)
    {
      std::vector<double> packed;
      for (const CellGaps &cell : gaps)
        packed.insert(packed.end(), {cell.to_cells, cell.to_wall});
      owners.take_smallest(make_array_view(packed));
      for (unsigned int c = 0; c < gaps.size(); ++c)
        gaps[c] = {packed[2 * c], packed[2 * c + 1]};
    }

    /**
     * The gap from every point of an owned cell among @p points (those of
     * the @p searched_cells, cell by cell, @p cell_of) to the nearest point
     * of another cell among them, measured along that point's normal, into
     * @p gaps of both cells.
     */
    void
    add_cell_gaps(const std::vector<std::shared_ptr<Membrane>> &membranes,
                  const std::vector<Vector<double>>            &x,
                  const std::optional<double>                   period,
                  const CellOwners                             &owners,
                  const std::vector<bool>                      &searched_cells,
                  const std::vector<Point<3>>                  &points,
                  const std::vector<unsigned int>              &cell_of,
                  std::vector<CellGaps>                        &gaps)
    {
      // The unit outward normal at every point, in the same order.
      std::vector<Tensor<1, 3>> normals;
      for (unsigned int c = 0; c < membranes.size(); ++c)
        if (searched_cells[c])
          for (const Tensor<1, 3> &w : membranes[c]->nodal_vector_areas(x[c]))
            normals.push_back(w / w.norm());
      // In a periodic segment the nearest point may lie across an end:
      // search the points wrapped into the segment and their images a
      // period before and after (points_in_segment(), three per point, in
      // that order).
      const std::vector<Point<3>> searched = points_in_segment(points, period);
      const unsigned int          copies   = searched.size() / points.size();
      namespace bgi                        = boost::geometry::index;
      const auto tree                      = pack_rtree_of_indices(searched);
      for (unsigned int i = 0; i < points.size(); ++i)
        {
          if (!owners.owns(cell_of[i]))
            continue;
          const Point<3>            p = searched[copies * i];
          std::vector<unsigned int> nearest;
          tree.query(bgi::nearest(p, 1) &&
                       bgi::satisfies([&](const unsigned int k) {
                         return cell_of[k / copies] != cell_of[i];
                       }),
                     std::back_inserter(nearest));
          if (nearest.empty())
            continue;
          const unsigned int j   = nearest.front() / copies;
          const double       gap = (p - searched[nearest.front()]) * normals[j];
          for (const unsigned int c : {cell_of[i], cell_of[j]})
            gaps[c].to_cells = std::min(gaps[c].to_cells, gap);
        }
    }
  } // namespace

  std::vector<CellGaps>
  measure_gaps(const std::vector<std::shared_ptr<Membrane>> &membranes,
               const std::vector<Vector<double>>            &x,
               const std::optional<double>                   wall_radius,
               const std::optional<double>                   period,
               const CellOwners                             &owners)
  {
    std::vector<CellGaps> gaps(membranes.size());
    // The points of the cells that may hold an owned point's nearest one
    // (the owned cells among them), with their cells.
    const std::vector<bool> searched_cells =
      CellBoxes(membranes, x, period).nearest_candidates(owners);
    std::vector<Point<3>>     points;
    std::vector<unsigned int> cell_of;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (searched_cells[c])
        for (const auto &dofs : membranes[c]->nodes())
          {
            const Point<3> p(x[c][dofs[0]], x[c][dofs[1]], x[c][dofs[2]]);
            points.push_back(p);
            cell_of.push_back(c);
            if (wall_radius && owners.owns(c))
              gaps[c].to_wall = std::min(gaps[c].to_wall,
                                         *wall_radius - std::hypot(p[1], p[2]));
          }
    if (membranes.size() > 1)
      add_cell_gaps(
        membranes, x, period, owners, searched_cells, points, cell_of, gaps);
    take_smallest(gaps, owners);
    return gaps;
  }
} // namespace rbc_ifem

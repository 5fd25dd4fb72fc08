#include <rbc_ifem/coupling/contact_gaps.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <cmath>

namespace rbc_ifem
{
  std::vector<CellGaps>
  measure_gaps(const std::vector<std::unique_ptr<Membrane>> &membranes,
               const std::vector<Vector<double>>            &x,
               const std::optional<double>                   wall_radius,
               const std::optional<double>                   period)
  {
    std::vector<CellGaps> gaps(membranes.size());

    // Every point with its cell.
    std::vector<Point<3>>     points;
    std::vector<unsigned int> cell_of;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      for (const auto &dofs : membranes[c]->nodes())
        {
          const Point<3> p(x[c][dofs[0]], x[c][dofs[1]], x[c][dofs[2]]);
          points.push_back(p);
          cell_of.push_back(c);
          if (wall_radius)
            gaps[c].to_wall =
              std::min(gaps[c].to_wall, *wall_radius - std::hypot(p[1], p[2]));
        }
    if (membranes.size() < 2)
      return gaps;

    // The unit outward normal at every point, in the same order.
    std::vector<Tensor<1, 3>> normals;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      for (const Tensor<1, 3> &w : membranes[c]->nodal_vector_areas(x[c]))
        normals.push_back(w / w.norm());

    // In a periodic segment the nearest point may lie across an end: search
    // the points wrapped into the segment and their images a period before
    // and after (points_in_segment(), three per point, in that order).
    const std::vector<Point<3>> searched = points_in_segment(points, period);
    const unsigned int          copies   = searched.size() / points.size();
    namespace bgi                        = boost::geometry::index;
    const auto tree                      = pack_rtree_of_indices(searched);
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        const Point<3>            p = searched[copies * i];
        std::vector<unsigned int> nearest;
        tree.query(bgi::nearest(p, 1) &&
                     bgi::satisfies([&](const unsigned int k) {
                       return cell_of[k / copies] != cell_of[i];
                     }),
                   std::back_inserter(nearest));
        const unsigned int j   = nearest.front() / copies;
        const double       gap = (p - searched[nearest.front()]) * normals[j];
        for (const unsigned int c : {cell_of[i], cell_of[j]})
          gaps[c].to_cells = std::min(gaps[c].to_cells, gap);
      }
    return gaps;
  }
} // namespace rbc_ifem

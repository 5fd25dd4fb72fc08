#include <rbc_ifem/coupling/cell_boxes.h>
#include <rbc_ifem/coupling/point_forces.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbc_ifem
{
  CellBoxes::CellBoxes(const std::vector<std::unique_ptr<Membrane>> &membranes,
                       const std::vector<Vector<double>>            &x,
                       const std::optional<double>                  &period)
    : period(period)
  {
    std::vector<Point<3>> points;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      {
        points.clear();
        for (const auto &dofs : membranes[c]->nodes())
          points.push_back(
            wrap_into_segment(node_position(x[c], dofs), period));
        boxes.emplace_back(points);
      }
  }

  std::vector<double>
  CellBoxes::shifts() const
  {
    if (!period)
      return {0.};
    return {0., -*period, *period};
  }

  double
  CellBoxes::distance(const unsigned int a, const unsigned int b) const
  {
    const auto &[a_low, a_high] = boxes[a].get_boundary_points();
    const auto &[b_low, b_high] = boxes[b].get_boundary_points();
    double nearest              = std::numeric_limits<double>::infinity();
    for (const double shift : shifts())
      {
        double squared = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double s   = d == 0 ? shift : 0.;
            const double gap = std::max(
              {0., b_low[d] + s - a_high[d], a_low[d] - b_high[d] - s});
            squared += gap * gap;
          }
        nearest = std::min(nearest, std::sqrt(squared));
      }
    return nearest;
  }

  double
  CellBoxes::farthest(const unsigned int a, const unsigned int b) const
  {
    const auto &[a_low, a_high] = boxes[a].get_boundary_points();
    const auto &[b_low, b_high] = boxes[b].get_boundary_points();
    double nearest              = std::numeric_limits<double>::infinity();
    for (const double shift : shifts())
      {
        double squared = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double s    = d == 0 ? shift : 0.;
            const double span = std::max(std::abs(b_high[d] + s - a_low[d]),
                                         std::abs(a_high[d] - b_low[d] - s));
            squared += span * span;
          }
        nearest = std::min(nearest, std::sqrt(squared));
      }
    return nearest;
  }

  std::vector<bool>
  CellBoxes::near_owned(const CellOwners &owners, const double range) const
  {
    std::vector<bool> near(boxes.size(), false);
    for (unsigned int a = 0; a < boxes.size(); ++a)
      if (owners.owns(a))
        for (unsigned int b = 0; b < boxes.size(); ++b)
          if (b == a || distance(a, b) < range)
            near[b] = true;
    return near;
  }

  std::vector<bool>
  CellBoxes::nearest_candidates(const CellOwners &owners) const
  {
    std::vector<bool> candidates(boxes.size(), false);
    for (unsigned int a = 0; a < boxes.size(); ++a)
      if (owners.owns(a))
        {
          // Every point of a has a point of b within farthest(a, b): no
          // cell beyond the least of those holds a nearest point.
          double bound = std::numeric_limits<double>::infinity();
          for (unsigned int b = 0; b < boxes.size(); ++b)
            if (b != a)
              bound = std::min(bound, farthest(a, b));
          for (unsigned int b = 0; b < boxes.size(); ++b)
            if (b == a || distance(a, b) <= bound)
              candidates[b] = true;
        }
    return candidates;
  }
} // namespace rbc_ifem

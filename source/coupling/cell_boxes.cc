#include <rbc_ifem/coupling/cell_boxes.h>
#include <rbc_ifem/coupling/point_forces.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbc_ifem
{
  CellBoxes::CellBoxes(const std::vector<std::shared_ptr<Membrane>> &membranes,
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

  template <typename AxisLength>
  double
  CellBoxes::over_images(const unsigned int a,
                         const unsigned int b,
                         const AxisLength  &length) const
  {
    const auto &[a_low, a_high] = boxes[a].get_boundary_points();
    const auto &[b_low, b_high] = boxes[b].get_boundary_points();
    double smallest             = std::numeric_limits<double>::infinity();
    for (const double shift : shifts())
      {
        double squared = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double s = d == 0 ? shift : 0.;
            const double l =
              length(a_low[d], a_high[d], b_low[d] + s, b_high[d] + s);
            squared += l * l;
          }
        smallest = std::min(smallest, std::sqrt(squared));
      }
    return smallest;
  }

  double
  CellBoxes::distance(const unsigned int a, const unsigned int b) const
  {
    return over_images(a,
                       b,
                       [](const double a_low,
                          const double a_high,
                          const double b_low,
                          const double b_high) {
                         return std::max({0., b_low - a_high, a_low - b_high});
                       });
  }

  double
  CellBoxes::farthest(const unsigned int a, const unsigned int b) const
  {
    return over_images(a,
                       b,
                       [](const double a_low,
                          const double a_high,
                          const double b_low,
                          const double b_high) {
                         return std::max(std::abs(b_high - a_low),
                                         std::abs(a_high - b_low));
                       });
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

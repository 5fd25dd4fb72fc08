#include <rbc_ifem/membrane/optical_tweezers.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace rbc_ifem
{
  Vector<double>
  bead_forces(const Membrane &membrane, const double attached_fraction)
  {
    const Vector<double>     &X     = membrane.reference_positions();
    const auto               &nodes = membrane.nodes();
    const std::vector<double> areas = membrane.nodal_areas(X);
    const double total = std::accumulate(areas.begin(), areas.end(), 0.);

    // Nodes ordered by x; each patch takes nodes from its end until it
    // holds the attached fraction of the area.
    std::vector<unsigned int> order(nodes.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(),
              order.end(),
              [&](const unsigned int a, const unsigned int b) {
                return X[nodes[a][0]] < X[nodes[b][0]];
              });
    Vector<double> f(X.size());
    const double   wanted = attached_fraction * total;
    for (const int side : {-1, 1})
      {
        std::vector<unsigned int> patch;
        double                    held = 0.;
        for (unsigned int k = 0; k < order.size() && held < wanted; ++k)
          {
            const unsigned int node =
              side < 0 ? order[k] : order[order.size() - 1 - k];
            patch.push_back(node);
            held += areas[node];
          }
        for (const unsigned int node : patch)
          f[nodes[node][0]] = side * areas[node] / held;
      }
    return f;
  }

  StretchDiameters
  stretch_diameters(const Membrane &membrane, const Vector<double> &x)
  {
    double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
    for (const auto &dofs : membrane.nodes())
      {
        x_min = std::min(x_min, x[dofs[0]]);
        x_max = std::max(x_max, x[dofs[0]]);
        y_min = std::min(y_min, x[dofs[1]]);
        y_max = std::max(y_max, x[dofs[1]]);
      }
    return {x_max - x_min, y_max - y_min};
  }
} // namespace rbc_ifem

#include <rbc_ifem/coupling/point_forces.h>
#include <rbc_ifem/coupling/pushing_force.h>

#include <numeric>

namespace rbc_ifem
{
  PushingForce::PushingForce(
    const std::vector<std::shared_ptr<Membrane>> &membranes,
    const std::vector<Tensor<1, 3>>              &cell_forces,
    const CellOwners                             &owners)
    : membranes(membranes)
    , cell_forces(cell_forces)
    , owners(owners)
    , weights(reference_point_areas(membranes))
  {
    AssertDimension(cell_forces.size(), membranes.size());
    for (std::vector<double> &w : weights)
      {
        const double area = std::accumulate(w.begin(), w.end(), 0.);
        for (double &a : w)
          a /= area;
      }
  }

  CellForceReport
  PushingForce::add_forces(const std::vector<Vector<double>> &x,
                           std::vector<Vector<double>>       &forces) const
  {
    CellForceReport report;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (owners.owns(c))
        {
          const auto &nodes = membranes[c]->nodes();
          for (unsigned int n = 0; n < nodes.size(); ++n)
            {
              const Tensor<1, 3> force = weights[c][n] * cell_forces[c];
              report.energy -= force * node_position(x[c], nodes[n]);
              add_node_force(forces[c], nodes[n], force);
            }
          report.external_force += cell_forces[c];
        }
    return report;
  }

  std::unique_ptr<CellForceStiffness>
  PushingForce::stiffness(const std::vector<Vector<double>> &) const
  {
    return nullptr; // E is linear in x
  }
} // namespace rbc_ifem

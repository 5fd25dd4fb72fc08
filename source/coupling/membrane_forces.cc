#include <rbc_ifem/coupling/membrane_forces.h>

namespace rbc_ifem
{
  MembraneElasticity::MembraneElasticity(
    const std::vector<std::unique_ptr<Membrane>> &membranes)
    : membranes(membranes)
  {}

  CellForceReport
  MembraneElasticity::add_forces(const std::vector<Vector<double>> &x,
                                 std::vector<Vector<double>> &forces) const
  {
    CellForceReport report;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      {
        cell_forces.reinit(x[c].size(), /*omit_zeroing_entries=*/true);
        report.energy +=
          membranes[c]->energy_and_forces(x[c], cell_forces).total();
        forces[c] += cell_forces;
      }
    return report;
  }

  Tether::Tether(const std::vector<std::unique_ptr<Membrane>> &membranes,
                 const double                                  stiffness)
    : membranes(membranes)
    , stiffness(stiffness)
  {}

  CellForceReport
  Tether::add_forces(const std::vector<Vector<double>> &x,
                     std::vector<Vector<double>>       &forces) const
  {
    CellForceReport report;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      {
        const Vector<double> &X = membranes[c]->reference_positions();
        for (unsigned int i = 0; i < x[c].size(); ++i)
          {
            const double displacement = x[c][i] - X[i];
            const double spring       = -stiffness * displacement;
            forces[c][i] += spring;
            report.external_force[membranes[c]->component(i)] += spring;
            report.energy += stiffness / 2. * displacement * displacement;
          }
      }
    return report;
  }
} // namespace rbc_ifem

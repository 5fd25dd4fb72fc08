#include <rbc_ifem/coupling/membrane_forces.h>

namespace rbc_ifem
{

  MembraneElasticity::MembraneElasticity(
    const std::vector<std::shared_ptr<Membrane>> &membranes,
    const CellOwners                             &owners)
    : membranes(membranes)
    , owners(owners)
  {}

  CellForceReport
  MembraneElasticity::add_forces(const std::vector<Vector<double>> &x,
                                 std::vector<Vector<double>> &forces) const
  {
    CellForceReport report;
    Vector<double>  cell_forces;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (owners.owns(c))
        {
          cell_forces.reinit(x[c].size(), /*omit_zeroing_entries=*/true);
          report.energy +=
            membranes[c]->energy_and_forces(x[c], cell_forces).total();
          forces[c] += cell_forces;
        }
    return report;
  }

  namespace
  {
    /// The membranes' K, one MembraneStiffness per cell, taken by the
    /// cell's owner only.
    class ElasticityStiffness : public CellForceStiffness
    {
    public:
      ElasticityStiffness(const unsigned int n_cells, const CellOwners &owners)
        : cells(n_cells)
        , owners(owners)
      {}

      void
      add_product(const std::vector<Vector<double>> &v,
                  std::vector<Vector<double>>       &results) const override
      {
        for (unsigned int c = 0; c < cells.size(); ++c)
          if (owners.owns(c))
            cells[c].vmult_add(results[c], v[c]);
      }

      void
      add_diagonal(std::vector<Vector<double>> &diagonal) const override
      {
        for (unsigned int c = 0; c < cells.size(); ++c)
          if (owners.owns(c))
            cells[c].add_diagonal(diagonal[c]);
      }

      std::vector<MembraneStiffness> cells;
      /// A copy: the owners when K was taken.
      const CellOwners owners;
    };

    /// K = k I of springs of stiffness k on the owned cells.
    class SpringStiffness : public CellForceStiffness
    {
    public:
      SpringStiffness(const double k, const CellOwners &owners)
        : k(k)
        , owners(owners)
      {}

      void
      add_product(const std::vector<Vector<double>> &v,
                  std::vector<Vector<double>>       &results) const override
      {
        for (unsigned int c = 0; c < v.size(); ++c)
          if (owners.owns(c))
            results[c].add(k, v[c]);
      }

      void
      add_diagonal(std::vector<Vector<double>> &diagonal) const override
      {
        for (unsigned int c = 0; c < diagonal.size(); ++c)
          if (owners.owns(c))
            diagonal[c].add(k);
      }

    private:
      const double     k;
      const CellOwners owners;
    };
  } // namespace

  std::unique_ptr<CellForceStiffness>
  MembraneElasticity::stiffness(const std::vector<Vector<double>> &x) const
  {
    auto result =
      std::make_unique<ElasticityStiffness>(membranes.size(), owners);
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (owners.owns(c))
        membranes[c]->stiffness(x[c], result->cells[c]);
    return result;
  }

  Tether::Tether(const std::vector<std::shared_ptr<Membrane>> &membranes,
                 const double                                  stiffness,
                 const CellOwners                             &owners)
    : membranes(membranes)
    , spring_constant(stiffness)
    , owners(owners)
  {}

  CellForceReport
  Tether::add_forces(const std::vector<Vector<double>> &x,
                     std::vector<Vector<double>>       &forces) const
  {
    CellForceReport report;
    for (unsigned int c = 0; c < membranes.size(); ++c)
      if (owners.owns(c))
        {
          const Vector<double> &X = membranes[c]->reference_positions();
          for (unsigned int i = 0; i < x[c].size(); ++i)
            {
              const double displacement = x[c][i] - X[i];
              const double spring       = -spring_constant * displacement;
              forces[c][i] += spring;
              report.external_force[membranes[c]->component(i)] += spring;
              report.energy +=
                spring_constant / 2. * displacement * displacement;
            }
        }
    return report;
  }

  std::unique_ptr<CellForceStiffness>
  Tether::stiffness(const std::vector<Vector<double>> &) const
  {
    return std::make_unique<SpringStiffness>(spring_constant, owners);
  }
} // namespace rbc_ifem

#include <rbc_ifem/coupling/membrane_forces.h>

namespace rbc_ifem
{

  namespace
  {
    /**
     * Add to @p results (one Vector per cell) what @p add_cell(c, result)
     * adds for each cell c that this rank owns, and every other rank's for
     * its cells: one reduction for all cells, none on one rank.
     */
    template <typename CellFunction>
    double
    add_by_owners(const CellOwners            &owners,
                  std::vector<Vector<double>> &results,
                  const CellFunction          &add_cell)
    {
      double scalar = 0.;
      if (!owners.shared())
        {
          for (unsigned int c = 0; c < results.size(); ++c)
            scalar += add_cell(c, results[c]);
          return scalar;
        }
      std::vector<Vector<double>> owned(results.size());
      for (unsigned int c = 0; c < results.size(); ++c)
        {
          owned[c].reinit(results[c].size());
          if (owners.owns(c))
            scalar += add_cell(c, owned[c]);
        }
      owners.add_up(owned, scalar);
      for (unsigned int c = 0; c < results.size(); ++c)
        results[c] += owned[c];
      return scalar;
    }
  } // namespace

  MembraneElasticity::MembraneElasticity(
    const std::vector<std::unique_ptr<Membrane>> &membranes,
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
    report.energy = add_by_owners(
      owners, forces, [&](const unsigned int c, Vector<double> &result) {
        cell_forces.reinit(x[c].size(), /*omit_zeroing_entries=*/true);
        const double energy =
          membranes[c]->energy_and_forces(x[c], cell_forces).total();
        result += cell_forces;
        return energy;
      });
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
        add_by_owners(owners,
                      results,
                      [&](const unsigned int c, Vector<double> &result) {
                        cells[c].vmult_add(result, v[c]);
                        return 0.;
                      });
      }

      void
      add_diagonal(std::vector<Vector<double>> &diagonal) const override
      {
        add_by_owners(owners,
                      diagonal,
                      [&](const unsigned int c, Vector<double> &result) {
                        cells[c].add_diagonal(result);
                        return 0.;
                      });
      }

      std::vector<MembraneStiffness> cells;
      /// A copy: the owners when K was taken.
      const CellOwners owners;
    };

    /// K = k I of springs of stiffness k.
    class SpringStiffness : public CellForceStiffness
    {
    public:
      explicit SpringStiffness(const double k)
        : k(k)
      {}

      void
      add_product(const std::vector<Vector<double>> &v,
                  std::vector<Vector<double>>       &results) const override
      {
        for (unsigned int c = 0; c < v.size(); ++c)
          results[c].add(k, v[c]);
      }

      void
      add_diagonal(std::vector<Vector<double>> &diagonal) const override
      {
        for (Vector<double> &d : diagonal)
          d.add(k);
      }

    private:
      const double k;
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

  Tether::Tether(const std::vector<std::unique_ptr<Membrane>> &membranes,
                 const double                                  stiffness)
    : membranes(membranes)
    , spring_constant(stiffness)
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
            const double spring       = -spring_constant * displacement;
            forces[c][i] += spring;
            report.external_force[membranes[c]->component(i)] += spring;
            report.energy += spring_constant / 2. * displacement * displacement;
          }
      }
    return report;
  }

  std::unique_ptr<CellForceStiffness>
  Tether::stiffness(const std::vector<Vector<double>> &) const
  {
    return std::make_unique<SpringStiffness>(spring_constant);
  }
} // namespace rbc_ifem

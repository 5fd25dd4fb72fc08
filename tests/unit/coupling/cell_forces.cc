// The cell forces of a CellPopulation (CellForce): two Evans-Fung cells,
// their membranes' elasticity and, optionally, a tether, at perturbed
// positions.
//
// - the forces are the exact negative gradient of the reported energy: the
//   central difference of E along a random direction v equals -F·v;
// - the elasticity is internal: its forces sum to zero and no external force
//   is reported;
// - the tether's external force is its springs' sum, -k Σ (x - X), and the
//   total of all forces then equals it.

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/membrane_forces.h>

#include "check.h"
#include "gradient_check.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <random>

using namespace rbc_ifem;

namespace
{
  std::vector<CellPlacement>
  two_cells()
  {
    return {CellPlacement{Point<3>(5., 0., 0.), Tensor<1, 3>({1., 0., 0.})},
            CellPlacement{Point<3>(15., 0., 0.), Tensor<1, 3>({1., 0., 0.})}};
  }

  CellParameters
  coarse_cells()
  {
    CellParameters cells;
    cells.surface_refinements = 2;
    return cells;
  }

  /// Every position moved by @p amplitude times a uniform random number.
  std::vector<Vector<double>>
  perturbed(const std::vector<Vector<double>> &x,
            const double                       amplitude,
            std::mt19937                      &random)
  {
    std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
    std::vector<Vector<double>>            result = x;
    for (Vector<double> &cell : result)
      for (double &entry : cell)
        entry += uniform(random);
    return result;
  }

  /// Σ of every point force.
  Tensor<1, 3>
  total(const std::vector<Tensor<1, 3>> &forces)
  {
    Tensor<1, 3> sum;
    for (const Tensor<1, 3> &f : forces)
      sum += f;
    return sum;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;
  std::mt19937                     random(1);

  // The elasticity alone.
  {
    CellPopulation cells(two_cells(), coarse_cells(), MembraneParameters());
    cells.set_positions(perturbed(cells.positions(), 0.05, random));
    const std::vector<Tensor<1, 3>> forces  = cells.compute_forces();
    double                          largest = 0.;
    for (const Tensor<1, 3> &f : forces)
      largest = std::max(largest, f.norm());
    std::cout << "elasticity: energy " << cells.energy()
              << " pN µm, largest point force " << largest << " pN\n";
    check.at_least("elasticity: energy of the perturbed cells [pN µm]",
                   cells.energy(),
                   1e-3);
    check.at_most("elasticity: |Σ F| / max |F_I| (internal forces)",
                  total(forces).norm() / largest,
                  1e-10);
    check.near("elasticity: no external force [pN]",
               cells.held_force().norm(),
               0.,
               0.);
    check_gradient(check, cells, "elasticity");
    check_stiffness(check, cells, "elasticity");
  }

  // With the cells held by springs of k = 50 pN/µm.
  {
    const double   k = 50.;
    CellPopulation cells(two_cells(), coarse_cells(), MembraneParameters());
    cells.add_force(
      std::make_unique<Tether>(cells.membranes(), k, cells.owners()));
    cells.set_positions(perturbed(cells.positions(), 0.05, random));
    const std::vector<Tensor<1, 3>> forces = cells.compute_forces();

    Tensor<1, 3> springs;
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        const Membrane &membrane = *cells.membranes()[c];
        for (unsigned int i = 0; i < cells.positions()[c].size(); ++i)
          springs[membrane.component(i)] -=
            k * (cells.positions()[c][i] - membrane.reference_positions()[i]);
      }
    std::cout << "tether: held force " << cells.held_force() << " pN, springs "
              << springs << " pN, Σ F " << total(forces) << " pN\n";
    check.near("tether: held force = -k Σ (x - X) [pN]",
               (cells.held_force() - springs).norm(),
               0.,
               1e-12 * springs.norm());
    check.near("tether: Σ F = held force [pN]",
               (total(forces) - cells.held_force()).norm(),
               0.,
               1e-9 * springs.norm());
    check_gradient(check, cells, "elasticity and tether");
    check_stiffness(check, cells, "elasticity and tether");
  }
  return check.exit_code();
}

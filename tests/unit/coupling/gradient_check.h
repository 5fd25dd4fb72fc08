#ifndef rbc_ifem_tests_unit_coupling_gradient_check_h
#define rbc_ifem_tests_unit_coupling_gradient_check_h

#include <rbc_ifem/coupling/cell_population.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

/**
 * Check that the forces of @p cells are the exact negative gradient of
 * their energy: along a random direction v, the central difference of E
 * equals -F·v to a relative 1e-6. The cells are left at their positions,
 * with their forces computed there.
 */
inline void
check_gradient(Checker                  &check,
               rbc_ifem::CellPopulation &cells,
               const std::string        &what)
{
  using namespace dealii;
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  const std::vector<Vector<double>>      x = cells.positions();
  std::vector<Vector<double>>            v = x;
  for (Vector<double> &cell : v)
    for (double &entry : cell)
      entry = uniform(random);

  // -F·v, point by point in the population's order.
  const std::vector<Tensor<1, 3>> forces      = cells.compute_forces();
  double                          directional = 0.;
  unsigned int                    point       = 0;
  for (unsigned int c = 0; c < cells.size(); ++c)
    for (const auto &dofs : cells.membranes()[c]->nodes())
      {
        for (unsigned int d = 0; d < 3; ++d)
          directional -= forces[point][d] * v[c][dofs[d]];
        ++point;
      }

  const double h         = 1e-6;
  const auto   energy_at = [&](const double s) {
    std::vector<Vector<double>> moved = x;
    for (unsigned int c = 0; c < x.size(); ++c)
      moved[c].add(s, v[c]);
    cells.set_positions(moved);
    cells.compute_forces();
    return cells.energy();
  };
  const double difference = (energy_at(h) - energy_at(-h)) / (2. * h);
  cells.set_positions(x);
  cells.compute_forces();
  std::cout << "  " << what << ": dE/ds " << difference << ", -F·v "
            << directional << '\n';
  check.near(what + ": -F·v against the central difference of E, relative",
             directional / difference,
             1.,
             1e-6);
}

/**
 * Check CellPopulation::stiffness_diagonal() at the last linearize(): at
 * every 37th point and each direction d, the diagonal entry equals
 * e_(i,d) · K e_(i,d), K applied to the unit displacement of that point
 * alone, to a relative 1e-12.
 */
inline void
check_stiffness_diagonal(Checker                        &check,
                         const rbc_ifem::CellPopulation &cells,
                         const std::string              &what)
{
  using namespace dealii;
  const std::vector<Tensor<1, 3>> diagonal = cells.stiffness_diagonal();
  double                          largest = 0., error = 0.;
  for (unsigned int i = 0; i < cells.n_points(); i += 37)
    for (unsigned int d = 0; d < 3; ++d)
      {
        std::vector<Tensor<1, 3>> unit(cells.n_points());
        unit[i][d]         = 1.;
        const double entry = cells.stiffness_product(unit)[i][d];
        largest            = std::max(largest, std::abs(entry));
        error              = std::max(error, std::abs(diagonal[i][d] - entry));
      }
  std::cout << "  " << what << ": largest diagonal entry " << largest
            << ", largest error " << error << '\n';
  check.at_most(what + ": |diag K - e·K e| / max |e·K e|",
                error / largest,
                1e-12);
}

/**
 * Check the tangent stiffness of @p cells (CellPopulation::linearize()):
 * along a random direction v, K v equals the central difference of the
 * forces, (F(x - hv) - F(x + hv))/(2h), to a relative 1e-6. The cells are
 * left at their positions, with their forces computed there.
 */
inline void
check_stiffness(Checker                  &check,
                rbc_ifem::CellPopulation &cells,
                const std::string        &what)
{
  using namespace dealii;
  std::mt19937                           random(13);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  const std::vector<Vector<double>>      x = cells.positions();
  std::vector<Tensor<1, 3>>              v(cells.n_points());
  for (Tensor<1, 3> &point : v)
    for (unsigned int d = 0; d < 3; ++d)
      point[d] = uniform(random);

  cells.linearize();
  const std::vector<Tensor<1, 3>> Kv = cells.stiffness_product(v);

  const double h         = 1e-6;
  const auto   forces_at = [&](const double s) {
    std::vector<Vector<double>> moved = x;
    unsigned int                point = 0;
    for (unsigned int c = 0; c < x.size(); ++c)
      for (const auto &dofs : cells.membranes()[c]->nodes())
        {
          for (unsigned int d = 0; d < 3; ++d)
            moved[c][dofs[d]] += s * v[point][d];
          ++point;
        }
    cells.set_positions(moved);
    return cells.compute_forces();
  };
  const std::vector<Tensor<1, 3>> plus = forces_at(h), minus = forces_at(-h);
  cells.set_positions(x);
  cells.compute_forces();
  double norm = 0., error = 0.;
  for (unsigned int i = 0; i < Kv.size(); ++i)
    {
      norm += Kv[i].norm_square();
      error += (Kv[i] - (minus[i] - plus[i]) / (2. * h)).norm_square();
    }
  std::cout << "  " << what << ": |K v| " << std::sqrt(norm)
            << ", |K v - difference| " << std::sqrt(error) << '\n';
  check.at_most(what + ": |K v - (F(x-hv) - F(x+hv))/2h| / |K v|",
                std::sqrt(error / norm),
                1e-6);
  check_stiffness_diagonal(check, cells, what);
}

#endif

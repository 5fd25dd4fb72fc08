// The contact forces (coupling/contact_forces.h) between two Evans-Fung
// cells face to face and a capillary wall close to one of them:
//
// - each gap potential's pressure is -dφ/dh (central differences), zero at
//   its range (repulsion) and at its minimum r0 (Morse);
// - the forces of each CellForce are the exact negative gradient of its
//   energy: the central difference of E along a random direction v equals
//   -F·v;
// - the cell-cell forces are internal: with the membranes' elasticity the
//   total force and torque vanish to round-off; the repulsion pushes the
//   cells apart, aggregation pulls them together beyond r0;
// - the wall pushes the cell back into the lumen: its external force points
//   to the axis;
// - measure_gaps() gives the gap the cells were placed at, and a negative
//   gap once a cell is pushed into the other;
// - in a periodic segment, the same pair with one cell moved by a period to
//   the far end feels the same forces and has the same gap across the ends;
// - two spheres of radius R ≫ 1/β attracted by the Morse potential alone
//   are at rest where the Derjaguin approximation puts them: the force
//   between spheres is F(h) = π R φ(h), zero where φ(h) = 0, at the gap
//   h* = r0 - ln 2/β (0.3095 µm; flat membranes rest at r0). The pair
//   density reproduces it as the membrane mesh is refined.

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/coupling/contact_gaps.h>

#include "check.h"
#include "gradient_check.h"

#include <deal.II/base/mpi.h>


using namespace rbc_ifem;

namespace
{
  CellParameters
  coarse_cells()
  {
    CellParameters cells;
    cells.surface_refinements = 3;
    return cells;
  }

  /// Move cell @p c by @p shift.
  void
  translate(CellPopulation     &cells,
            const unsigned int  c,
            const Tensor<1, 3> &shift)
  {
    std::vector<Vector<double>> x = cells.positions();
    for (unsigned int i = 0; i < x[c].size(); ++i)
      x[c][i] += shift[cells.membranes()[c]->component(i)];
    cells.set_positions(x);
  }

  /// Two cells facing each other along x, @p gap apart at their rims, the
  /// first a distance @p wall_gap from a wall of radius 5 µm.
  std::unique_ptr<CellPopulation>
  two_cells(const double          gap,
            const double          wall_gap,
            const CellParameters &shape = coarse_cells())
  {
    const Tensor<1, 3> axis({1., 0., 0.});
    auto               cells = std::make_unique<CellPopulation>(
      std::vector<CellPlacement>{{Point<3>(0., 0., 0.), axis},
                                               {Point<3>(10., 0., 0.), axis}},
      shape,
      MembraneParameters());
    // The gap is measured from the tangent planes of the nearest points,
    // which change as the cells close in: a few corrections find it.
    CellGaps start;
    for (unsigned int iteration = 0; iteration < 4; ++iteration)
      {
        start = measure_gaps(cells->membranes(), cells->positions(), 5.)[0];
        translate(*cells, 1, Tensor<1, 3>({gap - start.to_cells, 0., 0.}));
      }
    for (const unsigned int c : {0u, 1u})
      translate(*cells, c, Tensor<1, 3>({0., start.to_wall - wall_gap, 0.}));
    return cells;
  }

  Tensor<1, 3>
  total(const std::vector<Tensor<1, 3>> &forces)
  {
    Tensor<1, 3> sum;
    for (const Tensor<1, 3> &f : forces)
      sum += f;
    return sum;
  }

  Tensor<1, 3>
  torque(const std::vector<Point<3>>     &points,
         const std::vector<Tensor<1, 3>> &forces)
  {
    Tensor<1, 3> sum;
    for (unsigned int i = 0; i < points.size(); ++i)
      sum += cross_product_3d(points[i], forces[i]);
    return sum;
  }

  /// The axial force on cell 1 [pN] and the largest point force.
  std::pair<double, double>
  axial_force_on_second(CellPopulation &cells)
  {
    const std::vector<Tensor<1, 3>> forces = cells.compute_forces();
    const unsigned int first = cells.membranes()[0]->nodes().size();
    double             axial = 0., largest = 0.;
    for (unsigned int i = 0; i < forces.size(); ++i)
      {
        largest = std::max(largest, forces[i].norm());
        if (i >= first)
          axial += forces[i][0];
      }
    return {axial, largest};
  }

  void
  check_potential(Checker                   &check,
                  const GapPotential        &potential,
                  const std::string         &what,
                  const std::vector<double> &gaps)
  {
    for (const double h : gaps)
      {
        const double step = 1e-6;
        const double slope =
          (potential.energy(h + step) - potential.energy(h - step)) /
          (2. * step);
        const double p  = potential.pressure(h).first;
        const double dp = (potential.pressure(h + step).first -
                           potential.pressure(h - step).first) /
                          (2. * step);
        std::cout << "  " << what << " at h = " << h << ": p " << p
                  << ", -dφ/dh " << -slope << ", dp/dh "
                  << potential.pressure(h).second << " (difference " << dp
                  << ")\n";
        check.near(what + ": p = -dφ/dh", p, -slope, 1e-6 * (1. + std::abs(p)));
        check.near(what + ": dp/dh",
                   potential.pressure(h).second,
                   dp,
                   1e-5 * (1. + std::abs(dp)));
      }
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;

  const RepulsivePotential repulsion(10., 0.3);
  const MorsePotential     morse(0.3, 3.84, 0.49, 2.);
  check_potential(check, repulsion, "repulsion", {0.05, 0.15, 0.29});
  check_potential(check, morse, "Morse", {0.2, 0.49, 1.});
  check.near("repulsion: p(Δ) [pN/µm²]",
             repulsion.pressure(0.3).first,
             0.,
             1e-14);
  check.near("Morse: p(r0) [pN/µm²]", morse.pressure(0.49).first, 0., 1e-14);
  {
    const double e = std::exp(3.84 * (0.49 - 2.));
    check.near("Morse: φ(r0) = -D_e - φ(cutoff), shifted [pN/µm]",
               morse.energy(0.49),
               -0.3 - 0.3 * (e * e - 2. * e),
               1e-14);
  }

  // Repulsion and the wall: cells 0.15 µm apart, cell 0 0.1 µm from the wall.
  {
    auto           cells = two_cells(0.15, 0.1);
    const CellGaps gaps =
      measure_gaps(cells->membranes(), cells->positions(), 5.)[0];
    std::cout << "placed: gap between the cells " << gaps.to_cells
              << " µm, wall gap " << gaps.to_wall << " µm\n";
    check.near("measured gap between the cells [µm]",
               gaps.to_cells,
               0.15,
               1e-6);
    check.near("measured wall gap [µm]", gaps.to_wall, 0.1, 1e-9);

    add_interaction_forces(*cells, InteractionParameters(), 5., std::nullopt);
    const auto [axial, largest]            = axial_force_on_second(*cells);
    const std::vector<Tensor<1, 3>> forces = cells->compute_forces();
    const Tensor<1, 3>              held   = cells->held_force();
    std::cout << "repulsion and wall: axial force on cell 1 " << axial
              << " pN, held (wall) force " << held << " pN, Σ F "
              << total(forces) << " pN\n";
    check.at_least("repulsion pushes cell 1 away along +x [pN]", axial, 1.);
    check.at_most("the wall pushes cell 0 to the axis: held force along y [pN]",
                  held[1],
                  -1.);
    check.at_most("Σ F = the wall's force, relative to max |F|",
                  (total(forces) - held).norm() / largest,
                  1e-12);
    check_gradient(check, *cells, "elasticity, repulsion, wall");
    check_stiffness(check, *cells, "elasticity, repulsion, wall");
  }

  // Repulsion and aggregation, no wall: force and torque conserved.
  for (const double gap : {0.2, 0.8})
    {
      auto                  cells = two_cells(gap, 1.);
      InteractionParameters parameters;
      parameters.aggregation = true;
      add_interaction_forces(*cells, parameters, std::nullopt, std::nullopt);
      const std::vector<Tensor<1, 3>> forces = cells->compute_forces();
      const auto [axial, largest]            = axial_force_on_second(*cells);
      const Tensor<1, 3> moment              = torque(cells->points(), forces);
      std::cout << "gap " << gap
                << " µm, repulsion and aggregation: axial force on "
                << "cell 1 " << axial << " pN, Σ F " << total(forces)
                << " pN, Σ x × F " << moment << " pN µm\n";
      check.at_most("internal forces: |Σ F| / max |F|",
                    total(forces).norm() / largest,
                    1e-12);
      check.at_most("internal forces: |Σ x × F| / (10 µm max |F|)",
                    moment.norm() / (10. * largest),
                    1e-12);
      if (gap > 0.49)
        check.at_most("aggregation beyond r0 pulls cell 1 back [pN]",
                      axial,
                      -0.1);
      check_gradient(check, *cells, "elasticity, repulsion, aggregation");
      check_stiffness(check, *cells, "elasticity, repulsion, aggregation");
    }

  // Across the ends of a periodic segment of 20 µm: cell 0 moved by a
  // period, to x = 20, faces cell 1 at x ≈ 2.6 through the end.
  {
    const double          period = 20.;
    InteractionParameters parameters;
    parameters.aggregation = true;
    auto inside            = two_cells(0.2, 1.);
    auto across            = two_cells(0.2, 1.);
    translate(*across, 0, Tensor<1, 3>({period, 0., 0.}));
    add_interaction_forces(*inside, parameters, std::nullopt, std::nullopt);
    add_interaction_forces(*across, parameters, std::nullopt, period);
    const std::vector<Tensor<1, 3>> f_inside   = inside->compute_forces();
    const std::vector<Tensor<1, 3>> f_across   = across->compute_forces();
    double                          difference = 0., largest = 0.;
    for (unsigned int i = 0; i < f_inside.size(); ++i)
      {
        difference = std::max(difference, (f_inside[i] - f_across[i]).norm());
        largest    = std::max(largest, f_inside[i].norm());
      }
    const double gap_inside =
      measure_gaps(inside->membranes(), inside->positions(), std::nullopt)[0]
        .to_cells;
    const double gap_across = measure_gaps(across->membranes(),
                                           across->positions(),
                                           std::nullopt,
                                           period)[0]
                                .to_cells;
    std::cout << "across the periodic end: energy " << across->energy()
              << " pN µm (inside " << inside->energy()
              << "), largest force difference " << difference << " pN, gap "
              << gap_across << " µm (inside " << gap_inside << ")\n";
    check.at_most("periodic: forces across the end = inside, relative",
                  difference / largest,
                  1e-10);
    check.near("periodic: energy across the end = inside [pN µm]",
               across->energy(),
               inside->energy(),
               1e-10 * std::abs(inside->energy()));
    check.near("periodic: gap across the end [µm]",
               gap_across,
               gap_inside,
               1e-10);
  }

  // The rest gap of two spheres under the Morse attraction alone.
  {
    const double          r0 = 0.49, beta = 3.84;
    const double          derjaguin = r0 - std::log(2.) / beta;
    InteractionParameters morse_only;
    morse_only.repulsion_pressure = 0.;
    morse_only.aggregation        = true;
    std::cout << "two spheres of R = 3.75 µm, Morse only: rest gap (Derjaguin "
              << derjaguin << " µm)\n";
    std::vector<double> rest_gaps;
    for (const unsigned int refinements : {3u, 4u, 5u})
      {
        CellParameters spheres;
        spheres.shape               = ReferenceShape::sphere;
        spheres.surface_refinements = refinements;
        // The axial force on cell 1: positive (apart) below the rest gap.
        const auto force_at = [&](const double gap) {
          auto cells = two_cells(gap, 1., spheres);
          add_interaction_forces(*cells,
                                 morse_only,
                                 std::nullopt,
                                 std::nullopt);
          return axial_force_on_second(*cells).first;
        };
        double low = 0.2, high = 0.45;
        for (unsigned int step = 0; step < 20; ++step)
          (force_at(0.5 * (low + high)) > 0. ? low : high) = 0.5 * (low + high);
        rest_gaps.push_back(0.5 * (low + high));
        std::cout << "  surface refinements " << refinements << ": "
                  << rest_gaps.back() << " µm\n";
      }
    // The discrete sum approaches the continuum as the point spacing falls
    // below 1/β = 0.26 µm (0.41, 0.32, 0.31 µm at 3, 4, 5 refinements);
    // Derjaguin's own error is O(h/R), a few per cent of h.
    check.near("Morse rest gap of two spheres, finest membrane [µm]",
               rest_gaps.back(),
               derjaguin,
               0.03 * derjaguin);
    check.at_most("Morse rest gap: finer membranes come closer to Derjaguin",
                  std::abs(rest_gaps[2] - derjaguin),
                  0.1 * std::abs(rest_gaps[0] - derjaguin));
  }

  // Cell 1 pushed into cell 0: the gap turns negative.
  {
    auto cells = two_cells(0.15, 1.);
    translate(*cells, 1, Tensor<1, 3>({-0.3, 0., 0.}));
    const CellGaps gaps =
      measure_gaps(cells->membranes(), cells->positions(), std::nullopt)[1];
    std::cout << "overlapping by 0.15 µm: gap " << gaps.to_cells << " µm\n";
    check.near("gap of overlapping cells [µm]", gaps.to_cells, -0.15, 0.02);
  }
  return check.exit_code();
}

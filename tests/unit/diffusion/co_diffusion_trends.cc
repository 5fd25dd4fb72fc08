// The physics trends of CO uptake that any layout must show (the paper's
// Figs. 7 and 8), on a small mesh, through the same PlacedCells and
// solve_uptake() as the layouts experiment:
//
// - DM total grows with the number of cells N (uniform layouts, N = 1..7);
// - DM per cell falls with N;
// - clustered cells take up less than uniform ones at intermediate N;
// - the gas layer adds almost no resistance: once its αD is large, DM of
//   one cell does not depend on it.

#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/geometry/placed_cells.h>
#include <rbc_ifem/parameters.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <vector>

using namespace rbc_ifem;

namespace
{
  /// Defaults, on a small mesh: membranes 2 refinements, band 1.
  Parameters
  small_run()
  {
    Parameters p;
    p.cells.surface_refinements         = 2;
    p.mesh.diffusion_global_refinements = 1;
    p.mesh.diffusion_band_refinements   = 1;
    return p;
  }

  double
  dm(const Parameters &p, const LayoutKind kind, const unsigned int n_cells)
  {
    Parameters layout_run     = p;
    layout_run.layout.kind    = kind;
    layout_run.layout.n_cells = n_cells;
    TimerOutput       timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    const PlacedCells cells(layout_run.layout,
                            p.geometry,
                            p.cells,
                            p.cells.surface_refinements);
    const Uptake      uptake =
      UptakeSolver(p.geometry, p.mesh, p.diffusion, MPI_COMM_WORLD, timer)
        .solve(cells.membranes.membrane_surfaces());
    std::cout << "  " << name_of(kind, layout_kind_names()) << ", " << n_cells
              << " cells: DM " << uptake.dm_total << " µm³/(s Torr), per cell "
              << uptake.dm_total / n_cells << '\n';
    return uptake.dm_total;
  }
} // namespace

int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;
  const Parameters                 p = small_run();

  std::cout << "Uniform layouts\n";
  std::vector<double> uniform{0.};
  for (unsigned int n = 1; n <= 7; ++n)
    uniform.push_back(dm(p, LayoutKind::uniform, n));
  for (unsigned int n = 2; n <= 7; ++n)
    {
      const std::string N =
        " from N = " + std::to_string(n - 1) + " to " + std::to_string(n);
      check.at_least("DM total grows" + N + ": relative increase",
                     uniform[n] / uniform[n - 1] - 1.,
                     0.01);
      check.at_least("DM per cell falls" + N + ": relative decrease",
                     1. - (uniform[n] / n) / (uniform[n - 1] / (n - 1)),
                     0.001);
    }

  std::cout << "Clustered layouts\n";
  for (unsigned int n = 2; n <= 5; ++n)
    check.at_least("clustered below uniform, N = " + std::to_string(n) +
                     ": 1 - clustered/uniform",
                   1. - dm(p, LayoutKind::clustered, n) / uniform[n],
                   0.02);

  std::cout << "Gas layer permeability\n";
  Parameters high_gas = p, low_gas = p;
  high_gas.diffusion.gas_diffusivity *= 100.;
  low_gas.diffusion.gas_diffusivity *= 1e-5;
  check.near("DM of one cell with gas αD x 100 / DM with gas αD x 1",
             dm(high_gas, LayoutKind::uniform, 1) / uniform[1],
             1.,
             1e-3);
  // The check above could fail: a gas layer as resistive as tissue does
  // change DM.
  check.at_least("1 - DM with gas αD x 1e-5 / DM with gas αD x 1",
                 1. - dm(low_gas, LayoutKind::uniform, 1) / uniform[1],
                 0.05);
  return check.exit_code();
}

// mpirun: 1 2

// The cut-cell uptake solve on a fully distributed mesh, on however many
// ranks it runs (ctest: 1 and 2):
//
// - no rank holds the whole mesh, and the ranks share it evenly: on two
//   ranks, the rank holding the most cells (its own, its ghost layer and
//   their parents, 0.71 of them for a resting cell in the middle of the
//   capillary) holds at most 3/4 of them there, and at most 0.83 for a
//   cell at 3/10 of the capillary's length, whose refined band lies mostly
//   in one half: the slabs are balanced by the cells each coarse cell is
//   refined into (0.80 on 2026-12-07); slabs of equal numbers of coarse
//   cells gave the largest rank 0.87;
// - DM is the same on any number of ranks: membranes at Surface
//   refinements 2, Q2 on band refinements 1, against the value of one rank
//   (4.178838523 in the middle, the cut-cell parachute regression at
//   t = 0), to solver tolerance.

#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/geometry/placed_cells.h>
#include <rbc_ifem/parameters.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <iomanip>
#include <iostream>
#include <string>

using namespace rbc_ifem;

namespace
{
  /// The solve for one resting cell centred at @p position (a fraction of
  /// the capillary's length): the mesh's share on the largest rank at most
  /// @p largest_share, and DM against one rank's @p dm_one_rank.
  void
  check_cell_at(Checker     &check,
                const double position,
                const double largest_share,
                const double dm_one_rank)
  {
    const unsigned int n_ranks =
      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    Parameters p;
    p.layout.kind                     = LayoutKind::clustered;
    p.layout.n_cells                  = 1;
    p.layout.cluster_position         = position;
    p.cells.surface_refinements       = 2;
    p.mesh.diffusion_band_refinements = 1;
    p.diffusion.method                = DiffusionMethod::cut_cell;
    p.diffusion.degree                = 2;
    p.diffusion.linear_tolerance      = 1e-11;
    TimerOutput       timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    const PlacedCells cells(p.layout,
                            p.geometry,
                            p.cells,
                            p.cells.surface_refinements);
    const Uptake      uptake =
      UptakeSolver(p.geometry, p.mesh, p.diffusion, MPI_COMM_WORLD, timer)
        .solve(cells.membranes.membrane_surfaces());

    const std::string where = "cell at " + std::to_string(position) + ": ";
    const double      share =
      static_cast<double>(uptake.n_cells_largest_rank) / uptake.n_cells;
    std::cout << where << n_ranks << " rank(s): " << uptake.n_cells
              << " cells, " << uptake.n_cells_largest_rank
              << " on the largest rank; DM " << std::setprecision(10)
              << uptake.dm_total << '\n';
    if (n_ranks == 1)
      check.near(where + "share of the cells on the one rank", share, 1., 0.);
    else
      check.at_most(where + "share of the cells on the largest rank",
                    share,
                    largest_share);
    check.near(where + "DM against one rank's",
               uptake.dm_total,
               dm_one_rank,
               1e-7 * dm_one_rank);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports
  Checker check;
  check_cell_at(check, 0.5, 0.75, 4.178838523);
  check_cell_at(check, 0.3, 0.83, 4.140860272);
  return check.exit_code();
}

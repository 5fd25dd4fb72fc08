// mpirun: 1 2

// The cut-cell uptake solve on a fully distributed mesh, on however many
// ranks it runs (ctest: 1 and 2):
//
// - no rank holds the whole mesh: on two ranks or more, the rank holding the
//   most cells holds at most 3/4 of them (its own, its ghost layer and their
//   parents);
// - DM is the same on any number of ranks: one resting cell, membranes at
//   Surface refinements 2, Q2 on band refinements 1, against the value of
//   one rank (4.178838523, the cut-cell parachute regression at t = 0), to
//   solver tolerance.

#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/geometry/placed_cells.h>
#include <rbc_ifem/parameters.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <iostream>

using namespace rbc_ifem;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports

  Parameters p;
  p.layout.n_cells                  = 1;
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

  Checker      check;
  const double share =
    static_cast<double>(uptake.n_cells_largest_rank) / uptake.n_cells;
  std::cout << n_ranks << " rank(s): " << uptake.n_cells << " cells, "
            << uptake.n_cells_largest_rank << " on the largest rank; DM "
            << std::setprecision(10) << uptake.dm_total << '\n';
  if (n_ranks == 1)
    check.near("share of the cells on the one rank", share, 1., 0.);
  else
    check.at_most("share of the cells on the largest rank", share, 0.75);
  check.near("DM against one rank's",
             uptake.dm_total,
             4.178838523,
             1e-7 * 4.178838523);
  return check.exit_code();
}

// mpirun: 1 2 3 4

// The fluid mesh built by all ranks (create_distributed_mesh_hierarchy(),
// MeshZone): a periodic capillary refined once and twice more in a band
// around a ring of points that reaches across the periodic end (40 µm long).
// Every rank builds only its zone; together the ranks must hold the mesh built
// whole on one rank, cell for cell: the same number of active cells, each owned
// once (the sums of the owned cells' centres and levels over the ranks are
// the whole mesh's), and every coarser multigrid level the whole mesh
// coarsened as often. On 3 and 4 ranks a zone leaves coarse cells out. Built
// again with slabs of equal fine cells (fine_cells_per_coarse_cell()), the
// mesh is the same and the largest rank's share is near 1/P.

#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/mesh_hierarchy.h>
#include <rbc_ifem/geometry/mesh_zone.h>

#include "check.h"

#include <deal.II/base/mpi.h>

#include <cmath>
#include <iostream>

using namespace rbc_ifem;

namespace
{
  constexpr double period = 40.;

  /// The default capillary (radius 5 µm), 40 µm long: 16 layers of coarse
  /// cells, so that a zone of 3 or 4 ranks leaves some out.
  GeometryParameters
  long_capillary()
  {
    GeometryParameters geometry;
    geometry.capillary_length = period;
    return geometry;
  }
  const GeometryParameters geometry = long_capillary();

  /// Points on a ring of radius 3 µm at x = 0.5 µm and their images.
  std::vector<Point<3>>
  band_points()
  {
    std::vector<Point<3>> ring;
    for (unsigned int k = 0; k < 24; ++k)
      {
        const double angle = 2. * numbers::PI * k / 24.;
        ring.emplace_back(0.5, 3. * std::cos(angle), 3. * std::sin(angle));
      }
    return points_in_segment(ring, period);
  }

  void
  make_coarse(Triangulation<3> &mesh)
  {
    create_fluid_mesh(mesh, geometry, 0);
    add_end_periodicity(mesh);
  }

  void
  refine(Triangulation<3> &mesh, const MeshZone &zone)
  {
    zone.refine_global(mesh, 1);
    refine_near_points(mesh, band_points(), 0.5, 2, zone);
  }

  /// Sums over the active cells (locally owned ones, if distributed):
  /// the count, the centres' coordinates and the levels.
  std::vector<double>
  sums(const Triangulation<3> &mesh)
  {
    std::vector<double> s(5, 0.);
    for (const auto &cell : mesh.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          s[0] += 1.;
          for (unsigned int d = 0; d < 3; ++d)
            s[1 + d] += cell->center()[d];
          s[4] += cell->level();
        }
    return s;
  }

  void
  compare(Checker                &check,
          const std::string      &what,
          const Triangulation<3> &distributed,
          const Triangulation<3> &whole)
  {
    const std::vector<double> whole_sums = sums(whole);
    const std::vector<double> own        = sums(distributed);
    std::vector<double>       shared(own.size());
    Utilities::MPI::sum(own, MPI_COMM_WORLD, shared);
    const char *names[] = {
      "cells", "sum of x", "sum of y", "sum of z", "sum of levels"};
    for (unsigned int i = 0; i < 5; ++i)
      check.near(what + ": " + names[i],
                 shared[i],
                 whole_sums[i],
                 1e-9 * (1. + std::abs(whole_sums[i])));
  }

  /// The largest fraction of @p mesh's active cells that one rank owns.
  double
  largest_share(const Triangulation<3> &mesh)
  {
    return Utilities::MPI::max(sums(mesh)[0], MPI_COMM_WORLD) /
           mesh.n_global_active_cells();
  }

  /// @p fine and its coarser @p levels against @p whole and @p whole
  /// coarsened as often, cell for cell.
  void
  check_hierarchy(
    Checker                                                    &check,
    const std::string                                          &what,
    const parallel::fullydistributed::Triangulation<3>         &fine,
    const std::vector<std::shared_ptr<const Triangulation<3>>> &levels,
    const Triangulation<3>                                     &whole)
  {
    check.near(what + "global active cells",
               fine.n_global_active_cells(),
               whole.n_active_cells(),
               0.);
    compare(check, what + "fine mesh", fine, whole);
    check.near(what + "levels", levels.size() + 1, whole.n_levels(), 0.);
    for (unsigned int l = 0; l < levels.size(); ++l)
      {
        Triangulation<3> coarser(
          Triangulation<3>::limit_level_difference_at_vertices);
        make_coarse(coarser);
        refine(coarser, MeshZone());
        coarser.coarsen_global(levels.size() - l);
        compare(check,
                what + "level " + std::to_string(l),
                *levels[l],
                coarser);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Checker                          check;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);

  Triangulation<3> whole(Triangulation<3>::limit_level_difference_at_vertices);
  make_coarse(whole);
  refine(whole, MeshZone());
  parallel::fullydistributed::Triangulation<3> fine(MPI_COMM_WORLD);
  check_hierarchy(
    check,
    "",
    fine,
    create_distributed_mesh_hierarchy(fine, make_coarse, refine, true),
    whole);

  // Slabs of equal fine cells: the band at one end makes the slabs of equal
  // coarse cells unequal.
  parallel::fullydistributed::Triangulation<3> balanced(MPI_COMM_WORLD);
  check_hierarchy(
    check,
    "balanced, ",
    balanced,
    create_distributed_mesh_hierarchy(
      balanced,
      make_coarse,
      refine,
      true,
      fine_cells_per_coarse_cell(MPI_COMM_WORLD, make_coarse, refine, true)),
    whole);
  // Slabs of equal coarse cells give the largest rank 1.32, 1.86 and 2.38
  // times its share on 2, 3 and 4 ranks.
  const double unbalanced = largest_share(fine) * n_ranks;
  const double shared     = largest_share(balanced) * n_ranks;
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "largest rank's cells over 1/P of them: " << unbalanced
              << " in slabs of equal coarse cells, " << shared << " balanced"
              << std::endl;
  check.at_most("largest rank's cells over 1/P of them, balanced", shared, 1.3);

  Triangulation<3> coarse;
  make_coarse(coarse);
  unsigned int   in_zone = 0;
  const MeshZone zone(coarse,
                      Utilities::MPI::this_mpi_process(MPI_COMM_WORLD),
                      n_ranks,
                      period);
  for (const auto &cell : coarse.active_cell_iterators())
    in_zone += zone.contains(cell);
  const unsigned int largest = Utilities::MPI::max(in_zone, MPI_COMM_WORLD);
  if (n_ranks >= 3)
    check.at_most("coarse cells in the largest zone, of " +
                    std::to_string(coarse.n_active_cells()),
                  largest,
                  coarse.n_active_cells() - 1.);
  return check.exit_code();
}

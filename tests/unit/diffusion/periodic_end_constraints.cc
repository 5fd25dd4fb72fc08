// mpirun: 1 2 3 4

// Periodicity between the end faces of a diffusion mesh whose band was
// refined more at one end than at the other, partitioned by METIS and by
// z-order, on 1-4 ranks: match_end_refinement() refines the ends alike and
// make_end_periodicity_constraints() pairs their DoFs; the constraints close
// (with DoFTools::make_periodicity_constraints() and the ends left unlike,
// close() never returned on 3 and 4 ranks: doc/diffusion.md), and after
// AffineConstraints::distribute() of values made up at random every outlet
// DoF has the value of its inlet image, to round-off. The number of DoFs
// is the same on any number of ranks.

#include <rbc_ifem/diffusion/end_periodicity.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include "check.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <iostream>

using namespace rbc_ifem;

namespace
{
  using PVector = LinearAlgebra::distributed::Vector<double>;

  /**
   * The capillary's diffusion mesh, periodic, refined twice in a band
   * around a ring of points that crosses the inlet end (its images reach
   * the outlet), then once more in a corner of the outlet end only, and
   * matched (match_end_refinement()); partitioned by z-order if @p z_order,
   * by METIS otherwise.
   */
  void
  make_mesh(parallel::fullydistributed::Triangulation<3> &mesh,
            const bool                                    z_order)
  {
    GeometryParameters geometry;
    geometry.periodic = true;
    std::vector<Point<3>> ring;
    for (unsigned int i = 0; i < 400; ++i)
      {
        const double t = 2. * numbers::PI * i / 400.;
        ring.emplace_back(0.7 + 0.5 * std::sin(7. * t),
                          3.5 * std::cos(t),
                          3.5 * std::sin(t));
      }
    const unsigned int n_ranks =
      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    const auto description = TriangulationDescription::Utilities::
      create_description_from_triangulation_in_groups<3, 3>(
        [&](Triangulation<3> &serial) {
          create_diffusion_mesh(serial, geometry, 1);
          add_end_periodicity(serial);
          refine_near_points(serial,
                             points_in_segment(ring, geometry.period()),
                             0.5,
                             2);
          for (const auto &cell : serial.active_cell_iterators())
            if (cell->center()[0] > 19. && cell->center()[1] > 1.)
              cell->set_refine_flag();
          serial.execute_coarsening_and_refinement();
          match_end_refinement(serial);
        },
        [&](Triangulation<3> &serial, const MPI_Comm &, const unsigned int) {
          if (z_order)
            GridTools::partition_triangulation_zorder(n_ranks, serial);
          else
            GridTools::partition_triangulation(n_ranks, serial);
        },
        MPI_COMM_WORLD,
        n_ranks,
        Triangulation<3>::none,
        TriangulationDescription::Settings::construct_multigrid_hierarchy);
    create_capillary_mesh(mesh, description);
    add_end_periodicity(mesh);
  }

  /// Largest |P(outlet DoF) - P(inlet image)| over the end faces this rank
  /// sees, on all ranks.
  double
  largest_end_difference(const DoFHandler<3> &dof_handler, const PVector &P)
  {
    std::vector<GridTools::PeriodicFacePair<DoFHandler<3>::cell_iterator>> ends;
    GridTools::collect_periodic_faces(dof_handler,
                                      DiffusionBoundary::inlet_end,
                                      DiffusionBoundary::outlet_end,
                                      0,
                                      ends);
    const auto outlet_at = [&](const Point<3> &centre) {
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == DiffusionBoundary::outlet_end &&
                cell->face(f)->center().distance(centre) < 1e-8)
              return cell->face(f);
      return DoFHandler<3>::face_iterator();
    };
    double             largest = 0.;
    const unsigned int n       = dof_handler.get_fe().n_dofs_per_face();
    std::vector<types::global_dof_index> in(n), out(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == DiffusionBoundary::inlet_end)
            {
              const auto image = outlet_at(cell->face(f)->center() +
                                           Tensor<1, 3>({20., 0., 0.}));
              if (image.state() != IteratorState::valid)
                continue;
              cell->face(f)->get_dof_indices(in);
              image->get_dof_indices(out);
              for (unsigned int k = 0; k < n; ++k)
                largest = std::max(largest, std::abs(P[out[k]] - P[in[k]]));
            }
    return Utilities::MPI::max(largest, MPI_COMM_WORLD);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit); // every rank checks, rank 0 reports

  Checker check;
  for (const bool z_order : {false, true})
    {
      parallel::fullydistributed::Triangulation<3> mesh(MPI_COMM_WORLD);
      make_mesh(mesh, z_order);
      DoFHandler<3> dof_handler(mesh);
      dof_handler.distribute_dofs(FE_Q<3>(2));
      const IndexSet owned = dof_handler.locally_owned_dofs();
      IndexSet       relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      AffineConstraints<double> constraints(relevant);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      make_end_periodicity_constraints(dof_handler, constraints);
      constraints.make_consistent_in_parallel(owned, relevant, MPI_COMM_WORLD);
      constraints.close();

      PVector P(owned, relevant, MPI_COMM_WORLD);
      for (const auto dof : owned)
        P[dof] = std::sin(1.7 * dof); // made up, the same on any rank count
      constraints.distribute(P);
      P.update_ghost_values();
      const std::string name = z_order ? "z-order" : "METIS";
      std::cout << n_ranks << " ranks, " << name << ": " << dof_handler.n_dofs()
                << " DoFs\n";
      check.near(name + ": DoFs of the matched mesh, as on one rank",
                 dof_handler.n_dofs(),
                 77528,
                 0);
      check.at_most(name + ": largest |P(outlet) - P(inlet image)|",
                    largest_end_difference(dof_handler, P),
                    1e-12);
    }
  return check.exit_code();
}

/*
 * The yardstick of the uptake solve (issue 50, benchmarks/uptake_reference.sh):
 * a Q2 Poisson solve with ML AMG on the very mesh a DM solve ends with,
 * timed phase by phase under the same names.
 *
 *   poisson_reference FILE.prm
 *
 * FILE.prm is an `Experiment = diffusion` file. The program places its
 * layout's cells, builds the uptake mesh around them as the DM solve does
 * (UptakeMesh with the cut cells' resolution checks, CutCellGeometry), and
 * then solves -ΔP = 1 with P = 0 on the alveolar surface (P periodic
 * between the ends of a periodic segment) in FE_Q(Diffusion/Finite element
 * degree), with the AMG, the diagonal scaling and the CG tolerance of the
 * cut-cell solve (initialize_uptake_amg(), solve_scaled_cg()). It prints one
 * line,
 *
 *   reference: DOFS dofs, ITERATIONS iterations, dofs S, sparsity S,
 *   assemble S, amg S, solve S, total S
 *
 * (seconds; total is the sum of the five: the mesh is the DM solve's, not
 * the reference's). No cut cells, no level set: what an uptake solve would
 * cost if it were a plain Poisson problem on its mesh.
 */

#include <rbc_ifem/diffusion/cut_cell_geometry.h>
#include <rbc_ifem/diffusion/end_periodicity.h>
#include <rbc_ifem/diffusion/membrane_distance.h>
#include <rbc_ifem/diffusion/scaled_amg_solve.h>
#include <rbc_ifem/diffusion/uptake_mesh.h>
#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/placed_cells.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <iostream>
#include <memory>

using namespace dealii;
using namespace rbc_ifem;

namespace
{
  using Vector = TrilinosWrappers::MPI::Vector;
  using Matrix = TrilinosWrappers::SparseMatrix;

  /// The seconds of each phase, under the names the DM solve's
  /// timing.csv uses for the same work.
  struct PhaseSeconds
  {
    double dofs = 0., sparsity = 0., assemble = 0., amg = 0., solve = 0.;

    double
    total() const
    {
      return dofs + sparsity + assemble + amg + solve;
    }
  };

  /// The Poisson problem on one uptake mesh.
  class PoissonReference
  {
  public:
    PoissonReference(const CutCellGeometry     &geometry,
                     const DiffusionParameters &diffusion)
      : geometry(geometry)
      , diffusion(diffusion)
      , fe(diffusion.degree)
      , dof_handler(geometry.mesh())
      , communicator(geometry.mesh().get_communicator())
    {}

    /// Run every phase; the seconds of each, and the CG iterations.
    std::pair<PhaseSeconds, unsigned int>
    run()
    {
      PhaseSeconds seconds;
      seconds.dofs            = timed([this]() { set_up_dofs(); });
      seconds.sparsity        = timed([this]() { set_up_matrix(); });
      seconds.assemble        = timed([this]() { assemble(); });
      seconds.amg             = timed([this]() { build_preconditioner(); });
      unsigned int iterations = 0;
      seconds.solve           = timed([&]() { iterations = solve(); });
      return {seconds, iterations};
    }

    types::global_dof_index
    n_dofs() const
    {
      return dof_handler.n_dofs();
    }

  private:
    template <typename Work>
    double
    timed(const Work &work)
    {
      Timer timer(communicator, true);
      work();
      timer.stop();
      return timer.last_wall_time();
    }

    /// DoFs; hanging nodes, P = 0 on the alveolar surface, and the ends
    /// periodic as in the DM solve.
    void
    set_up_dofs()
    {
      dof_handler.distribute_dofs(fe);
      owned = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      constraints.reinit(relevant);
      DoFTools::make_hanging_node_constraints(dof_handler, constraints);
      VectorTools::interpolate_boundary_values(
        geometry.mapping(),
        dof_handler,
        DiffusionBoundary::alveolar_surface,
        Functions::ZeroFunction<3>(),
        constraints);
      if (geometry.period())
        make_end_periodicity_constraints(dof_handler, constraints);
      constraints.close();
    }

    void
    set_up_matrix()
    {
      DynamicSparsityPattern pattern(relevant);
      DoFTools::make_sparsity_pattern(dof_handler, pattern, constraints, false);
      SparsityTools::distribute_sparsity_pattern(pattern,
                                                 owned,
                                                 communicator,
                                                 relevant);
      matrix.reinit(owned, owned, pattern, communicator);
      rhs.reinit(owned, communicator);
    }

    /// ∫ ∇φ_i · ∇φ_j and ∫ φ_i on every owned cell.
    void
    assemble()
    {
      const QGauss<3>                      quadrature(fe.degree + 1);
      FEValues<3>                          fe_values(geometry.mapping(),
                            fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values);
      const unsigned int                   n = fe.n_dofs_per_cell();
      FullMatrix<double>                   local(n, n);
      dealii::Vector<double>               local_rhs(n);
      std::vector<types::global_dof_index> dofs(n);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            local     = 0.;
            local_rhs = 0.;
            for (const unsigned int q : fe_values.quadrature_point_indices())
              for (unsigned int i = 0; i < n; ++i)
                {
                  for (unsigned int j = 0; j < n; ++j)
                    local(i, j) += fe_values.shape_grad(i, q) *
                                   fe_values.shape_grad(j, q) *
                                   fe_values.JxW(q);
                  local_rhs(i) +=
                    fe_values.shape_value(i, q) * fe_values.JxW(q);
                }
            cell->get_dof_indices(dofs);
            constraints.distribute_local_to_global(
              local, local_rhs, dofs, matrix, rhs);
          }
      matrix.compress(VectorOperation::add);
      rhs.compress(VectorOperation::add);
    }

    /// The cut-cell solve's AMG (initialize_uptake_amg()).
    void
    build_preconditioner()
    {
      initialize_uptake_amg(amg, matrix, fe.degree);
    }

    /// The cut-cell solve's scaled CG and tolerance; its iterations.
    unsigned int
    solve()
    {
      Vector        x;
      SolverControl control(diffusion.max_linear_iterations,
                            diffusion.linear_tolerance);
      solve_scaled_cg(matrix, amg, owned, rhs, x, control);
      return control.last_step();
    }

    const CutCellGeometry            &geometry;
    const DiffusionParameters        &diffusion;
    const FE_Q<3>                     fe;
    DoFHandler<3>                     dof_handler;
    const MPI_Comm                    communicator;
    IndexSet                          owned, relevant;
    AffineConstraints<double>         constraints;
    Matrix                            matrix;
    Vector                            rhs;
    TrilinosWrappers::PreconditionAMG amg;
  };

  /// The uptake mesh of @p parameters' layout, as the DM solve builds it,
  /// and the cut-cell geometry on it (which holds the mapping).
  std::unique_ptr<CutCellGeometry>
  uptake_geometry(const Parameters       &parameters,
                  const MembraneSurfaces &surfaces,
                  UptakeMesh             &mesh,
                  TimerOutput            &timer)
  {
    const std::optional<double> period = parameters.geometry.period();
    const auto distance = std::make_shared<MembraneDistance>(surfaces.meshes(),
                                                             surfaces.mapping(),
                                                             period);
    std::unique_ptr<CutCellGeometry> geometry;
    mesh.build(surfaces,
               [&](const parallel::TriangulationBase<3> &triangulation,
                   const bool                            refine_ridges) {
                 CutCellGeometry::Options options;
                 options.refine_ridges = refine_ridges;
                 geometry              = std::make_unique<CutCellGeometry>(
                   triangulation,
                   surfaces,
                   distance,
                   parameters.diffusion.degree,
                   period,
                   options,
                   timer);
               });
    return geometry;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   communicator = MPI_COMM_WORLD;
  if (argc != 2)
    {
      std::cerr << "usage: poisson_reference FILE.prm" << std::endl;
      return 1;
    }
  ParameterHandler prm;
  Parameters       parameters;
  parameters.add_parameters(prm);
  // Entries of the program rbc-ifem (Experiment, Output directory) are
  // skipped: this one has no use for them.
  prm.parse_input(argv[1], "", true);
  parameters.validate();

  TimerOutput       timer(communicator,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  const PlacedCells cells(parameters.layout,
                          parameters.geometry,
                          parameters.cells,
                          parameters.cells.surface_refinements);
  UptakeMesh        mesh(parameters.geometry,
                  parameters.mesh,
                  DiffusionMethod::cut_cell,
                  communicator,
                  timer);
  // The surfaces outlive the geometry, which refers to them.
  const MembraneSurfaces surfaces = cells.membranes.membrane_surfaces();
  const std::unique_ptr<CutCellGeometry> geometry =
    uptake_geometry(parameters, surfaces, mesh, timer);

  PoissonReference reference(*geometry, parameters.diffusion);
  const auto [seconds, iterations] = reference.run();
  if (Utilities::MPI::this_mpi_process(communicator) == 0)
    std::cout << "reference: " << reference.n_dofs() << " dofs, " << iterations
              << " iterations, dofs " << seconds.dofs << " s, sparsity "
              << seconds.sparsity << " s, assemble " << seconds.assemble
              << " s, amg " << seconds.amg << " s, solve " << seconds.solve
              << " s, total " << seconds.total() << " s" << std::endl;
  return 0;
}

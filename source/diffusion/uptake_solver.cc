#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/diffusion/co_diffusion.h>
#include <rbc_ifem/diffusion/cut_cell_diffusion.h>
#include <rbc_ifem/diffusion/cut_cell_reaction.h>
#include <rbc_ifem/diffusion/uptake_mesh.h>
#include <rbc_ifem/diffusion/uptake_solver.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <iomanip>
#include <memory>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /**
     * The uptake mesh around the membranes, resolved, and the membrane
     * sink's problem on it: for cut cells the CutCellGeometry (which the
     * reaction's solves share) and CutCellDiffusion, for the multiplier
     * CODiffusion. What check() and the solves share.
     */
    class UptakeSetup
    {
    public:
      /**
       * The mesh and, for cut cells, the geometry; with
       * @p separate_insides the geometry the reaction needs. A diffusion
       * mesh too coarse for the multiplier's membranes is an InputError.
       */
      UptakeSetup(const GeometryParameters  &geometry,
                  const MeshParameters      &mesh_parameters,
                  const DiffusionParameters &d,
                  const MembraneSurfaces    &surfaces,
                  const bool                 separate_insides,
                  const MPI_Comm             communicator,
                  TimerOutput               &timer)
        : d(d)
        , timer(timer)
        , mesh(geometry, mesh_parameters, d.method, communicator, timer)
      {
        if (d.method == DiffusionMethod::cut_cell)
          build_cut_cells(geometry, surfaces, separate_insides);
        else
          build_multiplier(geometry,
                           surfaces,
                           mesh_parameters.diffusion_band_refinements,
                           communicator);
      }

      /// The membrane sink's problem on the mesh (for cut cells built here).
      DiffusionSolver &
      sink()
      {
        if (!sink_problem)
          sink_problem = std::make_unique<CutCellDiffusion>(
            *cut_cells,
            d,
            permeability(),
            DiffusionBoundary::alveolar_surface,
            timer);
        return *sink_problem;
      }

      /// The finite-uptake problem with the binding rate @p rate on the
      /// same mesh and geometry (cut cells only).
      std::unique_ptr<CutCellReaction>
      reaction(const double rate) const
      {
        return std::make_unique<CutCellReaction>(
          *cut_cells,
          d,
          permeability(),
          DiffusionBoundary::alveolar_surface,
          d.cytoplasm_permeability(),
          rate,
          timer);
      }

      /// The membrane sink's part of an Uptake: DM, and the mesh and the
      /// solve it took.
      Uptake
      sink_uptake() const
      {
        const parallel::TriangulationBase<3> &triangulation =
          mesh.triangulation();
        Uptake uptake;
        uptake.dm_total = sink_problem->total_flow() / d.alveolar_pressure;
        for (const double flow : sink_problem->membrane_flows())
          uptake.dm_cells.push_back(flow / d.alveolar_pressure);
        uptake.n_nodes = mesh.n_global_vertices();
        uptake.n_cells = triangulation.n_global_active_cells();
        uptake.n_cells_largest_rank =
          Utilities::MPI::max(triangulation.n_active_cells(),
                              triangulation.get_communicator());
        uptake.n_dofs     = sink_problem->n_dofs();
        uptake.iterations = sink_problem->n_iterations();
        return uptake;
      }

    private:
      std::function<double(unsigned int)>
      permeability() const
      {
        return [this](const unsigned int id) { return d.permeability(id); };
      }

      /// Cut cells: the geometry of the mesh that resolves the membranes.
      void
      build_cut_cells(const GeometryParameters &geometry,
                      const MembraneSurfaces   &surfaces,
                      const bool                separate_insides)
      {
        cut_cells = build_cut_cell_geometry(
          mesh, geometry, surfaces, d.degree, separate_insides, timer);
      }

      /// The multiplier set up on the mesh; a mesh too coarse for the
      /// membranes is an InputError naming the band refinements.
      void
      build_multiplier(const GeometryParameters &geometry,
                       const MembraneSurfaces   &surfaces,
                       const unsigned int        band_refinements,
                       const MPI_Comm            communicator)
      {
        mesh.build(
          surfaces,
          [&](const parallel::TriangulationBase<3> &triangulation, const bool) {
            auto multiplier =
              std::make_unique<CODiffusion>(d,
                                            permeability(),
                                            DiffusionBoundary::alveolar_surface,
                                            communicator,
                                            timer,
                                            geometry.period());
            try
              {
                multiplier->setup(triangulation, surfaces);
              }
            catch (const MembranesFinerThanMesh &e)
              {
                throw_too_coarse(e, band_refinements);
              }
            sink_problem = std::move(multiplier);
          });
      }

      [[noreturn]] static void
      throw_too_coarse(const MembranesFinerThanMesh &e,
                       const unsigned int            band_refinements)
      {
        std::ostringstream sizes;
        sizes << std::setprecision(2) << "the membrane cells ("
              << e.membrane_cell_size
              << " µm) are finer than the diffusion mesh cells around them ("
              << e.volume_cell_size << " µm)";
        throw InputError("Mesh/Diffusion band refinements",
                         std::to_string(band_refinements),
                         sizes.str() +
                           "; the diffusion mesh there must be about as "
                           "fine as the membranes or finer (the "
                           "multiplier's inf-sup condition): raise it, or "
                           "lower Cells/Surface refinements.");
      }

      const DiffusionParameters &d;
      TimerOutput               &timer;
      /// Declared first: what is set up on it goes first.
      UptakeMesh                       mesh;
      std::unique_ptr<CutCellGeometry> cut_cells;
      std::unique_ptr<DiffusionSolver> sink_problem;
    };

    /// Add the DL of @p reacting to @p uptake.
    void
    add_dl(Uptake                    &uptake,
           const CutCellReaction     &reacting,
           const DiffusionParameters &d)
    {
      uptake.dl_total      = reacting.dl_total();
      uptake.dl_iterations = reacting.n_iterations();
      uptake.dl_cells.clear();
      for (const double flow : reacting.membrane_flows())
        uptake.dl_cells.push_back(flow / d.alveolar_pressure);
    }
  } // namespace

  UptakeSolver::UptakeSolver(const GeometryParameters  &geometry,
                             const MeshParameters      &mesh,
                             const DiffusionParameters &diffusion,
                             const MPI_Comm             communicator,
                             TimerOutput               &timer)
    : geometry(geometry)
    , mesh(mesh)
    , diffusion(diffusion)
    , communicator(communicator)
    , timer(timer)
  {}

  void
  UptakeSolver::check(const MembraneSurfaces &surfaces) const
  {
    UptakeSetup(geometry,
                mesh,
                diffusion,
                surfaces,
                diffusion.uptake == CellUptake::reaction,
                communicator,
                timer);
  }

  Uptake
  UptakeSolver::solve(
    const MembraneSurfaces                             &surfaces,
    const std::function<void(const DiffusionSolver &)> &write_fields) const
  {
    return solve_sink_and_rates(surfaces,
                                diffusion.uptake == CellUptake::reaction ?
                                  std::vector<double>{
                                    diffusion.reaction_rate()} :
                                  std::vector<double>{},
                                write_fields)
      .front();
  }

  std::vector<Uptake>
  UptakeSolver::solve_for_rates(const MembraneSurfaces    &surfaces,
                                const std::vector<double> &rates) const
  {
    if (diffusion.method != DiffusionMethod::cut_cell)
      throw InputError("Diffusion/Method",
                       "Lagrange multiplier",
                       "DL needs the cell interiors in the mesh: cut cell.");
    AssertThrow(!rates.empty(), ExcMessage("No binding rates given."));
    return solve_sink_and_rates(surfaces, rates, {});
  }

  std::vector<Uptake>
  UptakeSolver::solve_sink_and_rates(
    const MembraneSurfaces                             &surfaces,
    const std::vector<double>                          &rates,
    const std::function<void(const DiffusionSolver &)> &write_fields) const
  {
    Timer       clock;
    UptakeSetup setup(
      geometry, mesh, diffusion, surfaces, !rates.empty(), communicator, timer);
    DiffusionSolver &sink = setup.sink();
    sink.assemble();
    sink.solve();
    const Uptake sink_uptake = setup.sink_uptake();
    if (rates.empty())
      {
        if (write_fields)
          write_fields(sink);
        std::vector<Uptake> uptakes{sink_uptake};
        uptakes.back().seconds = clock.wall_time();
        return uptakes;
      }
    std::vector<Uptake> uptakes;
    for (const double rate : rates)
      {
        const std::unique_ptr<CutCellReaction> reacting = setup.reaction(rate);
        reacting->assemble();
        reacting->solve();
        add_dl(uptakes.emplace_back(sink_uptake), *reacting, diffusion);
        if (write_fields && uptakes.size() == rates.size())
          write_fields(*reacting);
        uptakes.back().seconds = clock.wall_time();
        clock.restart();
      }
    return uptakes;
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/experiments/mesh_convergence_experiment.h>

#include <cmath>

namespace rbc_ifem
{
  void
  MeshConvergenceParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh convergence");
    add_parameter(prm,
                  "Number of levels",
                  n_levels,
                  "Experiment 'mesh convergence': level 0 is the mesh of "
                  "subsection Mesh and Cells/Surface refinements; each "
                  "further level refines the diffusion mesh's band and "
                  "the membranes once more.",
                  Patterns::Integer(2, 6));
    add_parameter(prm,
                  "Refine membranes",
                  refine_membranes,
                  "Refine the membranes with the band from level to level. "
                  "The Lagrange multiplier needs it (its membranes must "
                  "stay about twice as coarse as the mesh around them); "
                  "with cut cells false keeps Cells/Surface refinements on "
                  "every level, so that the table shows the convergence in "
                  "the diffusion mesh alone.");
    prm.leave_subsection();
  }

  MeshConvergenceExperiment::MeshConvergenceExperiment(
    const ExperimentContext         &context,
    const MeshConvergenceParameters &study)
    : UptakeExperiment(context)
    , study(study)
  {}

  void
  MeshConvergenceExperiment::setup()
  {
    coarsest =
      std::make_unique<const PlacedCells>(parameters.layout,
                                          parameters.geometry,
                                          parameters.cells,
                                          parameters.cells.surface_refinements);
  }

  unsigned int
  MeshConvergenceExperiment::membrane_refinements(
    const unsigned int level) const
  {
    return parameters.cells.surface_refinements +
           (study.refine_membranes ? level : 0);
  }

  void
  MeshConvergenceExperiment::execute()
  {
    std::vector<Uptake>                levels;
    std::unique_ptr<const PlacedCells> cells = std::move(coarsest);
    for (unsigned int level = 0; level < study.n_levels; ++level)
      {
        if (level > 0 && study.refine_membranes)
          cells =
            std::make_unique<const PlacedCells>(parameters.layout,
                                                parameters.geometry,
                                                parameters.cells,
                                                membrane_refinements(level));
        levels.push_back(
          uptake_solver(parameters.mesh.diffusion_band_refinements + level)
            .solve(cells->membranes.membrane_surfaces()));
        report("level " + std::to_string(level) + ", " +
                 std::to_string(levels.back().n_nodes) + " nodes",
               levels.back());
      }

    // Richardson extrapolation from the last three levels (h halves from
    // level to level): DM(h) = DM* + C h^p.
    const unsigned int L  = levels.size() - 1;
    const double       d2 = levels[L].dm_total, d1 = levels[L - 1].dm_total;
    const double       ratio =
      L >= 2 ? (d1 - levels[L - 2].dm_total) / (d2 - d1) : 0.;
    const bool   monotone = ratio > 1.;
    const double limit    = monotone ? d2 + (d2 - d1) / (ratio - 1.) : d2;
    if (monotone)
      pcout << "  extrapolated DM " << limit << " µm³/(s Torr), observed order "
            << std::log2(ratio) << std::endl;
    else
      pcout << "  the last levels do not converge monotonically; differences "
               "are taken from the finest level"
            << std::endl;

    CsvTable table("level,n_nodes,n_cells,n_dofs,dm_total,relative_change,"
                   "surface_refinements,band_refinements,iterations,seconds,"
                   "difference_from_limit");
    for (unsigned int l = 0; l <= L; ++l)
      {
        const Uptake &u = levels[l];
        CsvRow        row;
        row << l << u.n_nodes << u.n_cells << u.n_dofs << u.dm_total;
        if (l == 0)
          row << "nan";
        else
          row << std::abs(u.dm_total - levels[l - 1].dm_total) / u.dm_total;
        row << membrane_refinements(l)
            << parameters.mesh.diffusion_band_refinements + l << u.iterations
            << u.seconds << std::abs(u.dm_total - limit) / limit;
        table.add_row(row.str());
      }
    create_output_directory(parameters.output_directory, communicator);
    write_on_rank_0(communicator, [&]() {
      table.write(parameters.output_directory + "/convergence.csv");
    });
  }
} // namespace rbc_ifem

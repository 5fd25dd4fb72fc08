#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/experiments/layouts_experiment.h>

#include <cmath>
#include <numeric>

namespace rbc_ifem
{
  void
  LayoutStudyParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Layout study");
    add_selection(prm,
                  "Kinds",
                  kinds,
                  layout_kind_names(),
                  "Experiment 'layouts': the layout kinds to compare.");
    add_parameter(prm,
                  "Numbers of cells",
                  numbers_of_cells,
                  "Experiment 'layouts': the numbers of cells N to place "
                  "in the segment, each in every kind.",
                  Patterns::List(Patterns::Integer(1), 1));
    add_parameter(prm,
                  "Random seeds",
                  n_seeds,
                  "Experiment 'layouts': random layouts are drawn with "
                  "seeds Layout/Seed, Layout/Seed + 1, ...; layouts.csv "
                  "reports their mean and spread.",
                  Patterns::Integer(1));
    prm.leave_subsection();
  }

  LayoutsExperiment::LayoutsExperiment(const std::string           &name,
                                       const Parameters            &parameters,
                                       const LayoutStudyParameters &study,
                                       const ParameterHandler      &prm,
                                       const MPI_Comm communicator)
    : UptakeExperiment(name, parameters, prm, communicator)
    , study(study)
  {}

  void
  LayoutsExperiment::setup()
  {
    // A layout the study asks for, or an InputError that names the study.
    const auto study_layout = [&](const LayoutParameters &layout) {
      try
        {
          return CellLayout(layout, parameters.geometry, parameters.cells);
        }
      catch (const InputError &e)
        {
          throw InputError("Layout study/Numbers of cells",
                           std::to_string(layout.n_cells),
                           "the " + name_of(layout.kind, layout_kind_names()) +
                             " layout of that many cells is impossible: " +
                             e.what());
        }
    };
    for (const LayoutKind kind : study.kinds)
      for (const unsigned int n : study.numbers_of_cells)
        {
          samples.emplace_back();
          const unsigned int n_samples =
            kind == LayoutKind::random ? study.n_seeds : 1;
          for (unsigned int sample = 0; sample < n_samples; ++sample)
            {
              LayoutParameters layout = parameters.layout;
              layout.kind             = kind;
              layout.n_cells          = n;
              layout.seed             = parameters.layout.seed + sample;
              samples.back().push_back(std::make_unique<const PlacedCells>(
                study_layout(layout),
                parameters.geometry,
                parameters.cells,
                parameters.cells.surface_refinements));
            }
        }
  }

  void
  LayoutsExperiment::execute()
  {
    CsvTable table("layout,n_cells,hematocrit,dm_total,dm_per_cell,"
                   "dm_total_std,n_samples");
    for (const auto &layouts : samples)
      {
        std::vector<double> dm;
        double              hematocrit = 0.;
        for (const auto &cells : layouts)
          {
            const LayoutParameters &layout = cells->layout.parameters();
            const Uptake            uptake =
              solve(*cells, parameters.mesh.diffusion_band_refinements);
            report(name_of(layout.kind, layout_kind_names()) + ", " +
                     std::to_string(layout.n_cells) + " cells, seed " +
                     std::to_string(layout.seed),
                   uptake);
            dm.push_back(uptake.dm_total);
            hematocrit += cells->hematocrit() / layouts.size();
          }
        const double mean =
          std::accumulate(dm.begin(), dm.end(), 0.) / dm.size();
        double variance = 0.;
        for (const double x : dm)
          variance +=
            (x - mean) * (x - mean) / std::max<std::size_t>(1, dm.size() - 1);
        const LayoutParameters &layout = layouts.front()->layout.parameters();
        table.add(name_of(layout.kind, layout_kind_names()),
                  layout.n_cells,
                  hematocrit,
                  mean,
                  mean / layout.n_cells,
                  std::sqrt(variance),
                  dm.size());
      }
    create_output_directory(parameters.output_directory, communicator);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      table.write(parameters.output_directory + "/layouts.csv");
  }
} // namespace rbc_ifem

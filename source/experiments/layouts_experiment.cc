#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/experiments/layouts_experiment.h>

#include <cmath>
#include <numeric>

namespace rbc_ifem
{
  LayoutsExperiment::LayoutsExperiment(const ExperimentContext &context)
    : UptakeExperiment(context)
  {}

  void
  LayoutsExperiment::setup()
  {
    for (const auto &layouts :
         parameters.layout_study.layouts(parameters.layout))
      {
        samples.emplace_back();
        for (const LayoutParameters &layout : layouts)
          samples.back().push_back(std::make_unique<const PlacedCells>(
            study_layout(layout, parameters.geometry, parameters.cells),
            parameters.geometry,
            parameters.cells,
            parameters.cells.surface_refinements));
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
            const Uptake uptake = solve(*cells);
            report(cells->layout.description(), uptake);
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
    write_on_rank_0(communicator, [&]() {
      table.write(parameters.output_directory + "/layouts.csv");
      for (const auto &layouts : samples)
        for (const auto &cells : layouts)
          cells->layout.table().write(parameters.output_directory + "/" +
                                      cells->layout.file_name());
    });
  }
} // namespace rbc_ifem

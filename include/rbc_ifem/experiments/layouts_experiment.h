#ifndef rbc_ifem_experiments_layouts_experiment_h
#define rbc_ifem_experiments_layouts_experiment_h

#include <rbc_ifem/experiments/uptake_experiment.h>

#include <memory>
#include <vector>

namespace rbc_ifem
{
  /**
   * Experiment "layouts", the paper's Figs. 7 and 8 with rigid cells: DM for
   * every kind and number of cells of subsection Layout study (the other
   * entries from subsection Layout), random layouts over several seeds.
   * Writes layouts.csv: layout,n_cells,hematocrit,dm_total,dm_per_cell (the
   * means over the seeds), dm_total_std, n_samples; and every layout it
   * drew as layout_<kind>_<n>_<seed>.csv, which Layout/Kind = file reads.
   */
  class LayoutsExperiment : public UptakeExperiment
  {
  public:
    explicit LayoutsExperiment(const ExperimentContext &context);

  private:
    /// Every layout of the study, built and checked (InputError names the
    /// study's entry).
    void
    setup() override;
    void
    execute() override;

    /// Per kind and number of cells, the layouts of its samples (seeds).
    std::vector<std::vector<std::unique_ptr<const PlacedCells>>> samples;
  };
} // namespace rbc_ifem

#endif

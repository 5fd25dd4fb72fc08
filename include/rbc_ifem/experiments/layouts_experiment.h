#ifndef rbc_ifem_experiments_layouts_experiment_h
#define rbc_ifem_experiments_layouts_experiment_h

#include <rbc_ifem/experiments/uptake_experiment.h>

#include <memory>
#include <vector>

namespace rbc_ifem
{
  /**
   * The paper's layout study (subsection "Layout study"): every Kind for
   * every number of cells, several seeds for random layouts.
   */
  struct LayoutStudyParameters : public ExperimentParameters
  {
    std::vector<LayoutKind>   kinds{LayoutKind::uniform,
                                  LayoutKind::random,
                                  LayoutKind::clustered};
    std::vector<unsigned int> numbers_of_cells{1, 2, 3, 4, 5, 6, 7};
    unsigned int              n_seeds = 5;

    void
    add_parameters(ParameterHandler &prm) override;
  };

  /**
   * Experiment "layouts", the paper's Figs. 7 and 8: DM for every kind and
   * number of cells of subsection Layout study (the other entries from
   * subsection Layout), random layouts over several seeds. Writes
   * layouts.csv: layout,n_cells,hematocrit,dm_total,dm_per_cell (the means
   * over the seeds), dm_total_std, n_samples.
   */
  class LayoutsExperiment : public UptakeExperiment
  {
  public:
    LayoutsExperiment(const std::string           &name,
                      const Parameters            &parameters,
                      const LayoutStudyParameters &study,
                      const ParameterHandler      &prm,
                      const MPI_Comm               communicator);

  private:
    /// Every layout of the study, built and checked (InputError names the
    /// study's entry).
    void
    setup() override;
    void
    execute() override;

    const LayoutStudyParameters study;
    /// Per kind and number of cells, the layouts of its samples (seeds).
    std::vector<std::vector<std::unique_ptr<const PlacedCells>>> samples;
  };
} // namespace rbc_ifem

#endif

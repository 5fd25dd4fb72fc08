#ifndef rbc_ifem_experiments_flowing_layouts_experiment_h
#define rbc_ifem_experiments_flowing_layouts_experiment_h

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/experiments/experiment.h>

#include <memory>
#include <string>
#include <vector>

namespace rbc_ifem
{
  class RunParameters;

  /// Subsection "Flowing layouts": how a flowing run's steady DM is read.
  struct FlowingLayoutsParameters : public ExperimentParameters
  {
    /// The steady DM: the mean of the solves in the run's last window [s].
    double steady_window = 0.004;

    void
    add_parameters(ParameterHandler &prm) override;
    /// Throws InputError unless DM is solved during the runs, more than
    /// once in the steady window's run, and the cells can vary.
    void
    validate(const Parameters &parameters) const override;
  };

  /// What one flowing run of the study gave.
  struct FlowingLayoutResult
  {
    /// A DM solve of the run, and the smallest gap between cells then.
    struct Solve
    {
      double time, dm_total, smallest_gap; ///< [s], [µm³ s⁻¹ Torr⁻¹], [µm]
    };
    std::vector<Solve> solves;
    double             static_dm = 0.; ///< DM of the undeformed cells, t = 0
    double             steady_dm = 0.; ///< mean DM over the steady window
    double steady_spread         = 0.; ///< (max - min) / mean over that window
    double smallest_gap = 0.; ///< over the DM solves [µm]; inf: one cell
    double final_gap    = 0.; ///< at the last solve [µm]
    double deformation  = 0.; ///< mean deformation index at the end
    double wall_seconds = 0.;
  };

  /**
   * Experiment "flowing layouts", the paper's Figs. 6-8 with deforming
   * cells: every layout of subsection Layout study (each kind, each number
   * of cells, the random ones over several seeds, the other entries from
   * subsection Layout) carried by the plasma with the immersed method
   * (IFEMSimulation, as Experiment = flow with Immersed cells/Enabled) for
   * Time/Number of steps, DM solved every Immersed cells/Diffusion
   * interval steps. Usually in a periodic segment (Geometry/Periodic), with
   * the cells' contact forces of subsection Cell interactions (aggregation
   * as Cell interactions/Aggregation says).
   *
   * Each run is a flowing run of its own in Output
   * `directory/<kind>_<n>_<seed>/`, its parameters derived from these
   * (RunParameters::derive(): Experiment = flow and the run's layout), so its
   * parameters.prm reruns it alone; it writes the files of a flowing run there
   * (dm.csv, cells.csv with the gaps, flow.csv, the VTU series). The study
   * writes, after every run,
   *
   *  - layout_<kind>_<n>_<seed>.csv: the cells it placed (Layout/Kind = file
   *    reads it back);
   *  - flowing_layouts.csv: layout,n_cells,seed,hematocrit,time,dm_total,
   *    dm_per_cell,min_gap, a row per DM solve of every run;
   *  - flowing_layouts_summary.csv: per run the static DM (t = 0, the rigid
   *    layout) beside the steady DM of the deformed cells (the mean over the
   *    last Flowing layouts/Steady window), their change, and the gaps.
   *
   * A layout that places its cells exactly where an earlier one did (one
   * cell, uniform or clustered at the centre) is not run again: its rows
   * repeat the earlier run's under its own kind.
   */
  class FlowingLayoutsExperiment : public Experiment
  {
  public:
    FlowingLayoutsExperiment(const ExperimentContext        &context,
                             const FlowingLayoutsParameters &own);

    ~FlowingLayoutsExperiment() override;

  private:
    /// Every layout of the study built and checked, every run's parameters
    /// derived and checked.
    void
    setup() override;
    /// The runs, one after the other, the tables after each.
    void
    execute() override;

    /// The parameters of the flowing run of @p layout, from these: Experiment
    /// = flow in Output directory/<kind>_<n>_<seed>, its parameters.prm
    /// reruns it alone.
    std::unique_ptr<RunParameters>
    derive_run(const LayoutParameters &layout) const;

    /// Run @p r and read its DM history.
    FlowingLayoutResult
    run_one(const unsigned int r);

    /// Add the rows of run @p r, with @p result, to the tables.
    void
    add_rows(const unsigned int r, const FlowingLayoutResult &result);

    const FlowingLayoutsParameters own;
    /// The layout of each run, and the parameters it runs with.
    std::vector<LayoutParameters>               layouts;
    std::vector<std::unique_ptr<RunParameters>> runs;
    std::vector<double>                         hematocrits;
    /// The run whose cells each run's are (itself, or an earlier one).
    std::vector<unsigned int> same_cells_as;
    CsvTable history, summary; ///< flowing_layouts(_summary).csv
  };
} // namespace rbc_ifem

#endif

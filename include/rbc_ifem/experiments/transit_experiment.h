#ifndef rbc_ifem_experiments_transit_experiment_h
#define rbc_ifem_experiments_transit_experiment_h

#include <rbc_ifem/diffusion/oxygen_parameters.h>
#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/geometry/placed_cells.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * The parameters of experiment "transit": subsection Oxygen (the model)
   * and subsection Transit (how long and how).
   */
  struct TransitParameters : public ExperimentParameters
  {
    OxygenParameters oxygen;
    double           duration            = 0.75; ///< [s]
    bool             cells_flow          = true;
    double           time_step           = 0.002; ///< [s]
    double           time_step_tolerance = 0.;    ///< 0: fixed steps
    double           output_interval     = 0.05;  ///< [s]

    void
    add_parameters(ParameterHandler &prm) override;
    /// Cut cells, a duration of at least one step, and (for now) cells
    /// held in place.
    void
    validate(const Parameters &parameters) const override;
  };

  /**
   * Experiment "transit": O2 loading of the red cells of subsection Layout
   * over a capillary transit (CutCellOxygen). The segment follows the
   * cells, so following them for Transit/Duration covers the whole
   * capillary, P_A being the same all along it. For now the cells are held
   * where the layout puts them in plasma at rest (Transit/Cells flow =
   * false).
   *
   * Writes o2.csv (time,cell,saturation,mean_po2,uptake_rate: each cell's
   * volume means and the O2 through its membrane [µm³ O2/s]),
   * o2_balance.csv (time,dissolved,bound,wall_oxygen,balance_error: the O2
   * in the mesh, what entered through the alveolar surface since the
   * start [µm³ O2], and their mismatch relative to the larger of the
   * latter and the O2 in the mesh at the start),
   * o2_summary.csv (each cell's time to 95% of its rise to the
   * saturation in equilibrium with P_A, its end saturation and mean
   * PO2), cells.csv, and VTU of P and S (o2.pvd, o2_membranes.pvd with the
   * flux map).
   */
  class TransitExperiment : public Experiment
  {
  public:
    TransitExperiment(const ExperimentContext &context,
                      const TransitParameters &transit);

  private:
    void
    setup() override;
    void
    execute() override;

    const TransitParameters            transit;
    std::unique_ptr<const PlacedCells> cells;
  };
} // namespace rbc_ifem

#endif

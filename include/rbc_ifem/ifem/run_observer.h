#ifndef rbc_ifem_ifem_run_observer_h
#define rbc_ifem_ifem_run_observer_h

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/diffusion/uptake.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  /**
   * What an experiment records of a flowing run beyond the tables every run
   * writes (flow.csv, cells.csv, dm.csv): the experiment installs it in the
   * IFEMSimulation (add_observer()), which hands it the cells' shapes at
   * the start and at every output step, and every CO uptake solve with the
   * gaps between the cells then, adds its words to the progress line, and
   * has it write its tables whenever it writes its own. The shear
   * experiment's Taylor deformation and the flowing layouts' DM history are
   * two.
   *
   * Observers are not part of checkpoints: an experiment that installs one
   * runs without Immersed cells/Resume.
   */
  class RunObserver
  {
  public:
    virtual ~RunObserver() = default;

    /// The shapes of the cells at @p time [s].
    virtual void
    record(const double time, const std::vector<CellShape> &shapes) = 0;

    /**
     * The CO uptake solved at @p time [s], and the smallest gap between the
     * membranes of two cells then [µm] (infinite for a single cell).
     */
    virtual void
    record_uptake(const double /*time*/,
                  const Uptake & /*uptake*/,
                  const double /*smallest_gap*/)
    {}

    /// What the progress line says of @p shapes (", name value"), or "".
    virtual std::string
    progress(const std::vector<CellShape> &) const
    {
      return "";
    }

    /// Write the observer's tables into @p directory (rank 0's job).
    virtual void
    write_tables(const std::string &directory) const = 0;
  };
} // namespace rbc_ifem

#endif

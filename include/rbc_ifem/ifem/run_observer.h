#ifndef rbc_ifem_ifem_run_observer_h
#define rbc_ifem_ifem_run_observer_h

#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/diffusion/uptake.h>

#include <algorithm>
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
   * Observers are part of checkpoints: what state() returns is saved with
   * the run, and restore() is handed it back when the run resumes, so that
   * a resumed run's observer holds what it would have in one go.
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

    /**
     * What the observer has recorded, for a checkpoint (packed()). An
     * observer that keeps a record over the run overrides it and restore();
     * one that keeps nothing (the default: "") needs neither.
     */
    virtual std::string
    state() const
    {
      return "";
    }

    /// Take back what state() returned when the checkpoint was written.
    virtual void
    restore(const std::string & /*state*/)
    {}
  };

  /// @p values as bytes, for RunObserver::state(): unpacked() gives them
  /// back exactly.
  inline std::string
  packed(const std::vector<double> &values)
  {
    return std::string(reinterpret_cast<const char *>(values.data()),
                       values.size() * sizeof(double));
  }

  /// The values packed() into @p bytes.
  inline std::vector<double>
  unpacked(const std::string &bytes)
  {
    std::vector<double> values(bytes.size() / sizeof(double));
    std::copy(bytes.begin(),
              bytes.begin() + values.size() * sizeof(double),
              reinterpret_cast<char *>(values.data()));
    return values;
  }
} // namespace rbc_ifem

#endif

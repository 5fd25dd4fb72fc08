#ifndef rbc_ifem_ifem_checkpoint_h
#define rbc_ifem_ifem_checkpoint_h

#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/ifem/run_record.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// Everything a resumed flowing run needs: the run's parameters and
  /// record, the fluid, the membranes.
  struct CheckpointState
  {
    unsigned int                n_ranks = 0;
    std::string                 parameters; ///< the run's parameters.prm
    RunRecord                   record;
    FluidState                  fluid;
    std::vector<Vector<double>> positions; ///< of each cell's points [µm]

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &n_ranks &parameters &record &fluid &positions;
    }
  };

  /// What a run that resumes from a checkpoint is: what the checkpoint must
  /// match.
  struct ResumingRun
  {
    std::string  parameters; ///< its parameters.prm
    unsigned int n_ranks;
    std::size_t  n_fluid_dofs;
    unsigned int n_cells;
    std::size_t  n_point_values; ///< of the first cell's positions
    unsigned int n_steps;        ///< Time/Number of steps
  };

  /**
   * The checkpoints of a flowing run: checkpoint.bin in the output
   * directory, and the one before it, checkpoint_previous.bin. A file
   * starts with the lines
   *
   *   rbc-ifem checkpoint
   *   format F        what the file holds (Checkpoint::format)
   *   layout L        layout_fingerprint() of the version that wrote it
   *   bytes N         the payload's size
   *   crc32 C         the payload's CRC-32
   *
   * and then the payload, a boost binary archive of a CheckpointState. A
   * file of another format or layout is refused by name, not misread; a
   * truncated or damaged one is refused before anything is allocated for
   * it beyond its size.
   */
  class Checkpoint
  {
  public:
    /**
     * The format of what a checkpoint holds. Raise it (to the date) when
     * layout_fingerprint() changes, and add the pair to the table of
     * tests/unit/ifem/checkpoint_format.cc, which fails until then.
     */
    static constexpr unsigned int format = 20261205;

    /**
     * A fingerprint of what a checkpoint holds: the CRC-32 of the serialised
     * empty state of a run of two cells with DL (the tables' headers, no
     * rows), so that a member added, removed or retyped anywhere in a
     * CheckpointState, or a column added to flow.csv, cells.csv or dm.csv,
     * changes it.
     */
    static std::uint32_t
    layout_fingerprint();

    /// The checkpoints in @p directory.
    explicit Checkpoint(const std::string &directory);

    /// checkpoint.bin's path.
    std::string
    path() const;

    /**
     * Write @p state as checkpoint.bin (on rank 0 of @p communicator; the
     * state is the same on every rank), the one before kept as
     * checkpoint_previous.bin.
     */
    void
    write(const CheckpointState &state, const MPI_Comm communicator) const;

    /**
     * Read checkpoint.bin and check that it can resume @p run: throws
     * InputError naming Immersed cells/Resume and why it cannot be used (it
     * does not exist, another format or layout, truncated, damaged, other
     * ranks or DoFs), or the first parameter that differs from the run's
     * that wrote it (other than those a resume may change), or Time/Number
     * of steps if the run would not go beyond it.
     */
    CheckpointState
    read(const ResumingRun &run) const;

  private:
    /// The payload of checkpoint.bin, checked; throws the reason it cannot
    /// be used as a std::runtime_error.
    std::string
    payload() const;

    /// Throw InputError naming the first parameter of @p run (other than
    /// those a resume may change) whose value differs from @p written's.
    void
    check_parameters(const std::string &written, const ResumingRun &run) const;

    /// Throw InputError if @p state does not fit @p run.
    void
    check_sizes(const CheckpointState &state, const ResumingRun &run) const;

    const std::string directory;
  };
} // namespace rbc_ifem

#endif

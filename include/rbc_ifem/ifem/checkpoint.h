#ifndef rbc_ifem_ifem_checkpoint_h
#define rbc_ifem_ifem_checkpoint_h

#include <rbc_ifem/fluid/fluid_problem.h>
#include <rbc_ifem/geometry/cell_records.h>
#include <rbc_ifem/ifem/run_record.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Everything a resumed flowing run needs: the run's parameters and
   * record, the fluid, the membranes. All of it is the same on every rank
   * but the fluid's cell values, which each rank keeps of its own cells.
   */
  struct CheckpointState
  {
    std::string                 parameters; ///< the run's parameters.prm
    RunRecord                   record;
    FluidState                  fluid;
    std::vector<Vector<double>> positions; ///< of each cell's points [µm]
    std::vector<std::string>    observers; ///< each RunObserver::state()
    /**
     * This rank's share of FluidProblem::cell_values(): to write, its own
     * cells'; read, the records of the blocks it read, of any cells
     * (CellRecords::to_owners() hands them to the ranks that own them now).
     * Not part of serialize(): each rank writes its own block.
     */
    CellRecords fluid_cells;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &parameters &record &fluid &positions &observers;
    }
  };

  /// What a run that resumes from a checkpoint is: what the checkpoint must
  /// match.
  struct ResumingRun
  {
    std::string  parameters; ///< its parameters.prm
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
   *   bytes N         the size of all that follows the header
   *   crc32 C         the shared part's CRC-32
   *   shared S        the shared part's size
   *   blocks B        the number of fluid blocks
   *   block S C       each block's size and CRC-32, B lines
   *
   * and then the shared part, a boost binary archive of a CheckpointState,
   * and the fluid blocks, one per rank of the run that wrote it: that
   * rank's CheckpointState::fluid_cells (CellRecords::to_bytes()). The
   * ranks write their blocks at once (write_in_rank_order()). A resume on
   * any number of ranks reads them in turn (rank r the blocks r, r + P,
   * ...) and hands each cell's values to its owner: the records are keyed
   * by cell, not by DoF or rank. A file of another format or layout is
   * refused by name, not misread; a truncated or damaged one is refused
   * before anything is allocated for it beyond its size.
   *
   * A new checkpoint is written whole to checkpoint.bin.part and synced to
   * the disk; then checkpoint.bin becomes checkpoint_previous.bin and the
   * new file checkpoint.bin, each in one rename. A run killed at any moment
   * leaves a complete checkpoint.bin (the last one or the new one), and a
   * resume that finds checkpoint.bin missing or damaged resumes from
   * checkpoint_previous.bin and says so.
   */
  class Checkpoint
  {
  public:
    /**
     * The format of what a checkpoint holds. Raise it (to the date, with a
     * two-digit serial for that day's changes: YYYYMMDDNN) when
     * layout_fingerprint() changes, and add the pair to the table of
     * tests/unit/ifem/checkpoint_format.cc, which fails until then.
     */
    static constexpr unsigned int format = 2026120601;

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

    /**
     * The checkpoint files in @p directory and in its folders one level
     * down (the runs of a study), sorted; none if it does not exist.
     */
    static std::vector<std::string>
    find_in(const std::string &directory);

    /// checkpoint.bin's path.
    std::string
    path() const;

    /// Whether checkpoint.bin or checkpoint_previous.bin is there.
    bool
    exists() const;

    /// checkpoint_previous.bin's path.
    std::string
    previous_path() const;

    /**
     * Write @p state as checkpoint.bin, the one before kept as
     * checkpoint_previous.bin (see the class text); collective on
     * @p communicator, each rank writing its fluid block. Throws OutputError
     * with the cause if it cannot; the checkpoints from before stay then.
     */
    void
    write(const CheckpointState &state, const MPI_Comm communicator) const;

    /**
     * Read checkpoint.bin, or checkpoint_previous.bin if checkpoint.bin is
     * missing or damaged (resumed_from() says which and why), and check that
     * it can resume @p run (collective on @p communicator, which reads it
     * on any number of ranks): throws InputError naming Immersed
     * cells/Resume and why neither can be used (they do not exist, another
     * format or layout, truncated, damaged), or why the one read cannot
     * (other DoFs or cells), or the first parameter that differs from the
     * run's that
     * wrote it (other than those a resume may change), or Time/Number of
     * steps if the checkpoint is beyond it (at it, the run is finished and
     * the resume only writes its tables again).
     */
    CheckpointState
    read(const ResumingRun &run, const MPI_Comm communicator);

    /// The file read() resumed from, and why if not checkpoint.bin.
    const std::string &
    resumed_from() const;

  private:
    /// What the header of a checkpoint file says is in it.
    struct Contents;

    /// The header of @p file and its shared part, checked; throws the
    /// reason it cannot be used as a std::runtime_error.
    Contents
    contents(const std::string &file) const;

    /// The state in @p file with the fluid blocks of this rank of
    /// @p communicator; throws as contents().
    CheckpointState
    read_file(const std::string &file, const MPI_Comm communicator) const;

    /// The state in @p file, or nothing and @p why_not (the first failing
    /// rank's reason, on every rank of @p communicator).
    std::optional<CheckpointState>
    load(const std::string &file,
         std::string       &why_not,
         const MPI_Comm     communicator) const;

    /// Make checkpoint.bin checkpoint_previous.bin as well.
    void
    keep_as_previous() const;

    /// Put the directory's renames on the disk.
    void
    sync_directory() const;

    /// Throw InputError naming the first parameter of @p run (other than
    /// those a resume may change) whose value differs from @p written's.
    void
    check_parameters(const std::string &written, const ResumingRun &run) const;

    /// Throw InputError if @p state does not fit @p run.
    void
    check_sizes(const CheckpointState &state, const ResumingRun &run) const;

    const std::string directory;
    /// Whether write() keeps checkpoint.bin as checkpoint_previous.bin: not
    /// after a resume that found it unusable.
    bool rotate = true;
    /// What resumed_from() says.
    std::string source;
  };
} // namespace rbc_ifem

#endif

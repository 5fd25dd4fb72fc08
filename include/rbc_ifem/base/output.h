#ifndef rbc_ifem_base_output_h
#define rbc_ifem_base_output_h

#include <rbc_ifem/base/field_data.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/data_out.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

/**
 * Writers for the files every experiment produces. Each file appears under
 * its final name only once it is complete (written to a temporary name,
 * then renamed), so a crashed run never leaves a file that looks whole.
 */
namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Create the run's output directory (rank 0), or throw InputError on
   * every rank, naming `Output directory`, if that is impossible.
   */
  void
  create_output_directory(const std::string &directory,
                          const MPI_Comm     communicator);

  /**
   * Throw InputError on every rank, naming `Output directory` and the cause
   * (such as "Read-only file system"), if rank 0 cannot create a file in
   * @p directory, or, where it does not exist yet, in the folder it would
   * be created in. Creates nothing that stays.
   */
  void
  check_writable(const std::string &directory, const MPI_Comm communicator);

  /**
   * VTU flags for every file we write: deal.II's default, the best zlib
   * compression, spends two thirds of a large run's output time in zlib;
   * the fastest level costs little in size.
   */
  DataOutBase::VtkFlags
  fast_vtk_flags();

  /**
   * @p data_out (its patches built) as the file @p path, with
   * @p field_data, complete or not at all (write_file_atomically()).
   */
  template <int dim, int spacedim>
  void
  write_vtu(const DataOutInterface<dim, spacedim> &data_out,
            const std::string                     &path,
            const FieldData                       &field_data = {});

  /**
   * What DataOutInterface::write_vtu_with_pvtu_record() writes, each piece
   * with @p field_data: every rank its piece NAME_CCCC.RANK.vtu, rank 0 the
   * NAME_CCCC.pvtu that joins them, whose name it returns (CCCC the
   * @p counter, four digits).
   */
  template <int dim, int spacedim>
  std::string
  write_vtu_pieces(const DataOutInterface<dim, spacedim> &data_out,
                   const std::string                     &directory,
                   const std::string                     &name,
                   const unsigned int                     counter,
                   const MPI_Comm                         communicator,
                   const FieldData                       &field_data = {});

  /**
   * The same for the ranks @p writers of @p communicator only (sorted; the
   * others have nothing to show and write nothing): each its piece
   * NAME_CCCC.RANK.vtu, the first of them the NAME_CCCC.pvtu that joins
   * them. Call it on the @p writers alone; it waits for no other rank.
   */
  template <int dim, int spacedim>
  std::string
  write_vtu_pieces(const DataOutInterface<dim, spacedim> &data_out,
                   const std::string                     &directory,
                   const std::string                     &name,
                   const unsigned int                     counter,
                   const std::vector<unsigned int>       &writers,
                   const MPI_Comm                         communicator,
                   const FieldData                       &field_data = {});

  /// Write NAME.pvd listing (time, file) pairs, on rank @p writer of
  /// @p communicator only.
  void
  write_pvd(const std::string                                 &directory,
            const std::string                                 &name,
            const std::vector<std::pair<double, std::string>> &records,
            const MPI_Comm                                     communicator,
            const unsigned int                                 writer = 0);

  /**
   * Write @p path through @p writer, via the temporary file PATH.part and a
   * rename, and note it among the files this process has written
   * (written_files()). Throws OutputError naming the file and the cause if
   * it cannot be written; the `.part` is removed then, and a file of that
   * name from before stays as it was.
   */
  void
  write_file_atomically(const std::string                         &path,
                        const std::function<void(std::ostream &)> &writer);

  /// write_file_atomically() of the ready @p text.
  void
  write_text_atomically(const std::string &path, const std::string &text);

  /**
   * @p bytes as the file @p path, on the disk (fsync) when it returns.
   * Throws OutputError with the cause, and removes what it wrote of @p path.
   */
  void
  write_synced_file(const std::string &path, const std::string &bytes);

  /**
   * Write @p head, rank 0's (the others' is ignored), and after it every
   * rank's @p block in rank order as the file @p path, each rank its own
   * part at once (MPI-IO), on the disk when it returns (collective on
   * @p communicator). Throws OutputError with the cause on every rank that
   * failed; call it in write_together().
   */
  void
  write_in_rank_order(const std::string &path,
                      const std::string &head,
                      const std::string &block,
                      const MPI_Comm     communicator);

  /**
   * Rename @p from to @p to, replacing @p to in one step, and note @p to
   * among the files written (written_files()); throws OutputError with the
   * cause.
   */
  void
  rename_written_file(const std::string &from, const std::string &to);

  /**
   * What the ranks of @p communicator (by default this process alone) have
   * written into @p directory, for the closing line of a run (collective;
   * the list is rank 0's): the
   * tables, parameter files, checkpoints and .pvd records by name (sorted),
   * each subdirectory as "NAME/ (N files)". VTU and PVTU files are left out:
   * the .pvd files list them.
   */
  std::string
  written_files(const std::string &directory,
                const MPI_Comm     communicator = MPI_COMM_SELF);

  /**
   * Create @p directory if needed and write @p text (parameter_text()) there
   * as parameters.prm, the parameters as the run uses them (rank 0).
   */
  void
  write_parameters(const std::string &text,
                   const std::string &directory,
                   const MPI_Comm     communicator);

  /**
   * A volume mesh for ParaView: each rank writes the cells it owns, with
   * their material id and owning rank, as NAME_0000.RANK.vtu, rank 0 the
   * NAME_0000.pvtu that joins them and NAME.pvd. The boundary faces go to
   * NAME_boundary.vtu / .pvd with their boundary id.
   */
  void
  write_volume_mesh(const Triangulation<3> &triangulation,
                    const std::string      &directory,
                    const std::string      &name,
                    const MPI_Comm          communicator);

  /**
   * All membrane surfaces in one NAME.vtu, curved with @p mapping, with the
   * cell index as cell data. Written by rank 0; returns the file's name
   * (for a .pvd record). @p add_fields(i, data_out), if given, adds the
   * fields of membrane i (the same names on every membrane) to its DataOut
   * before the patches are built; the file carries @p field_data.
   */
  std::string
  write_membranes(
    const std::vector<const Triangulation<2, 3> *>           &surfaces,
    const MappingQ<2, 3>                                     &mapping,
    const std::string                                        &directory,
    const std::string                                        &name,
    const MPI_Comm                                            communicator,
    const std::function<void(unsigned int, DataOut<2, 3> &)> &add_fields = {},
    const FieldData                                          &field_data = {});
  /// A wall time as a person reads it: "8.4 s", "7 min 05 s", "2 h 03 min".
  std::string
  duration_text(const double seconds);

  /**
   * The end of a progress line: "[wall 25 s, about 7 min 30 s left]", from
   * the @p elapsed seconds that @p done steps took and the @p left steps to
   * go (at the same pace).
   */
  std::string
  time_left_text(const double       elapsed,
                 const unsigned int done,
                 const unsigned int left);

  /**
   * The peak resident memory of the largest rank in MB, and on more than
   * one rank that of rank 0 and the least to most of the others: "X MB
   * (largest over ranks; rank 0 A MB, the others B-C MB)". Rank 0 alone
   * builds the meshes whole (doc/scaling.md), which the split shows.
   * Collective.
   */
  std::string
  peak_memory_text(const MPI_Comm communicator);

  /// timing.csv (section,calls,wall_seconds) from a TimerOutput, rank 0.
  void
  write_timing(const TimerOutput &timer,
               const std::string &directory,
               const MPI_Comm     communicator);
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_base_input_files_h
#define rbc_ifem_base_input_files_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * A file a run reads, named by a parameter: the entry
   * ("Subsection/.../Entry") and the path as the run uses it (resolved:
   * resolve_file_parameters()).
   */
  struct InputFile
  {
    std::string entry;
    std::string path;
  };

  /**
   * Every file-name entry of @p prm (pattern Patterns::FileName) whose value
   * is a relative path is set to that path taken from @p folder, the folder
   * of the parameter file just read: a parameter file names its inputs
   * relative to itself, wherever the program runs. Absolute paths and empty
   * values stay as they are. Called after parsing the file and before the
   * --set changes, which are relative to the working directory.
   */
  void
  resolve_file_parameters(ParameterHandler &prm, const std::string &folder);

  /**
   * The name of the copy of @p input in a run's output directory:
   * inputs/ and its file name (a folder of its own, so that no input named
   * like an output, cells.csv say, is overwritten), which the run's
   * parameters.prm gives as the entry's value.
   */
  std::string
  copy_name(const InputFile &input);

  /**
   * The .prm @p text (parameter_text()) with the value of each input's
   * entry replaced by copy_name(): what the run records, so that
   * `rbc-ifem OUTPUT/parameters.prm` reads the copies beside it.
   */
  std::string
  with_input_copies(const std::string            &text,
                    const std::vector<InputFile> &inputs);

  /**
   * Copy each of @p inputs into @p directory as copy_name() (rank 0, each
   * copy complete or not at all). A copy that is the input itself (a run of
   * OUTPUT/parameters.prm into OUTPUT) is left alone; so is an existing copy
   * when @p keep_existing (a resumed run keeps the inputs it started from).
   */
  void
  copy_input_files(const std::vector<InputFile> &inputs,
                   const std::string            &directory,
                   const bool                    keep_existing,
                   const MPI_Comm                communicator);
} // namespace rbc_ifem

#endif

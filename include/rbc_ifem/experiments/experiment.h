#ifndef rbc_ifem_experiments_experiment_h
#define rbc_ifem_experiments_experiment_h

#include <rbc_ifem/base/run_options.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <string>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The parameters of an experiment's own subsection (Shear, Stretching,
   * ...), if it has one: declared and bound like the model's (see
   * GeometryParameters), and checked against the model's parameters once
   * the experiment is chosen.
   */
  class ExperimentParameters
  {
  public:
    virtual ~ExperimentParameters() = default;

    virtual void
    add_parameters(ParameterHandler &prm) = 0;

    /// Throw InputError if these do not go with @p parameters.
    virtual void
    validate(const Parameters &parameters) const;
  };

  /**
   * When a run creates its output directory and writes parameters.prm.
   * Before the work, for runs that write as they go (a flowing run: its
   * tables grow while it runs, and parameters.prm says what is running).
   * After it, for experiments whose files all come from finished work: a run
   * that fails, or finds its input impossible half-way (a diffusion mesh too
   * coarse for the membranes of a layout), then leaves nothing behind, and
   * execute() creates the directory (create_output_directory()) just before
   * it writes.
   */
  enum class ParametersFile
  {
    before_work,
    after_work
  };

  /**
   * What every experiment is made from (the registry gives it): its
   * registry name, the model's parameters, every parameter of the run as
   * read (for parameters.prm), the ranks it runs on and the command line's
   * options.
   */
  struct ExperimentContext
  {
    std::string             name;
    const Parameters       &parameters;
    const ParameterHandler &prm;
    MPI_Comm                communicator;
    RunOptions              options = {};
  };

  /**
   * One kind of run of the program, named by the parameter Experiment; the
   * registry (experiments/registry.h) lists them all. An experiment is a
   * type: it implements setup() and execute(), and run() does what every
   * experiment does around them, in this order:
   *
   *  1. the opening line "rbc-ifem: experiment 'NAME' on N rank(s)", and
   *     the Output directory checked: it can be written, and it holds no
   *     earlier run's checkpoints this run would replace (RunOptions);
   *  2. setup(): build and check everything the parameters ask for. An
   *     impossible request throws InputError here, before anything is
   *     written (the constructors build nothing);
   *  3. with ParametersFile::before_work, the output directory and in it
   *     parameters.prm: the parameters as the run uses them;
   *  4. execute(): the experiment's work and its files;
   *  5. with ParametersFile::after_work, parameters.prm;
   *  6. timing.csv (section,calls,wall_seconds) from @ref timer, the list of
   *     the files written (from what was written: written_files()), and the
   *     peak memory.
   */
  class Experiment
  {
  public:
    /**
     * The experiment of @p context; @p parameters_file says when
     * parameters.prm is written.
     */
    Experiment(const ExperimentContext &context,
               const ParametersFile     parameters_file);

    virtual ~Experiment() = default;

    /// The whole run, steps 1-6 above.
    void
    run();

  protected:
    /// Build and check; write nothing. Does nothing unless overridden.
    virtual void
    setup();

    /// The experiment's work and its files.
    virtual void
    execute() = 0;

    const std::string  name;
    const Parameters   parameters;
    const MPI_Comm     communicator;
    ConditionalOStream pcout; ///< rank 0's standard output
    /**
     * The sections of the run, for timing.csv: rank 0's own clock, since a
     * TimerOutput on the world communicator warns at length when an
     * exception unwinds through it.
     */
    TimerOutput timer;
    /// Every parameter of the run as read: what parameters.prm holds.
    const std::string parameter_file_text;

    /// The command line's options (--overwrite, --force).
    const RunOptions options;

  private:
    /**
     * Throw InputError if the Output directory cannot be written, or holds
     * checkpoints of an earlier run that this one, neither resuming nor
     * told to overwrite, would replace; remove them with --overwrite.
     */
    void
    check_output_directory() const;

    const ParametersFile parameters_file;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_experiments_registry_h
#define rbc_ifem_experiments_registry_h

#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /// One entry of the registry: an experiment the parameter Experiment names.
  struct ExperimentType
  {
    std::string name;
    /// What it does and writes, for the documentation of Experiment.
    std::string documentation;
    /// A new object of its own subsection's parameters, or null.
    std::function<std::unique_ptr<ExperimentParameters>()> make_parameters;
    /// The experiment of a context and its own parameters (null if it has
    /// none).
    std::function<std::unique_ptr<Experiment>(const ExperimentContext &,
                                              const ExperimentParameters *)>
      create;
  };

  /**
   * Every experiment of the program, in the order the documentation lists
   * them: the one list of their names, which the parameter Experiment, main()
   * and the tests (rbc-ifem --list-experiments) read. To add an
   * experiment, write its class and add its line here
   * (experiments/registry.cc).
   */
  const std::vector<ExperimentType> &
  experiment_types();

  /// One entry of a derived run (RunParameters::derive()): "" for the top.
  struct ParameterChange
  {
    std::string subsection;
    std::string entry;
    std::string value;
  };

  /// The shortest text that a .prm file reads back as exactly @p value.
  std::string
  exact_text(const double value);

  /**
   * Everything a parameter file sets, in one ParameterHandler: Experiment,
   * the model's Parameters and every experiment's own subsection, each
   * declared with its default and bound to the objects here, so that
   * reading a file fills them. Not copyable: the handler refers to them.
   */
  class RunParameters
  {
  public:
    RunParameters();
    RunParameters(const RunParameters &) = delete;
    RunParameters &
    operator=(const RunParameters &) = delete;

    /**
     * Read @p filename, then each of @p changes ("Subsection/Name=value",
     * the command line's --set), and check what can be checked without
     * building anything. Throws InputError, naming the file or the change,
     * the parameter and the value, if the file cannot be read, holds an
     * unknown entry or a value outside its pattern, or asks for something
     * impossible.
     */
    void
    read(const std::string              &filename,
         const std::vector<std::string> &changes = {});

    /**
     * Take every value of another run's parameter file @p text
     * (parameter_text()), then @p changes, and check the result: a run
     * derived from another, whose parameters.prm is exactly what it runs.
     */
    void
    derive(const std::string                  &text,
           const std::vector<ParameterChange> &changes);

    /// The experiment the parameters name, ready to run() with @p options.
    std::unique_ptr<Experiment>
    create_experiment(const MPI_Comm    communicator,
                      const RunOptions &options = {}) const;

    /**
     * What read() found odd in the file but ran with (read_parameter_file()):
     * entries set twice, a file that sets nothing.
     */
    const std::vector<std::string> &
    read_warnings() const;

    /// The model's parameters as read.
    const Parameters &
    model() const;

    /// Every parameter, as read: what parameters.prm shows.
    const ParameterHandler &
    handler() const;

    /// Every parameter with its documentation and default, as a .prm file.
    void
    print(std::ostream &out) const;

  private:
    /// Set one "Subsection/Name=value" of the command line.
    void
    set(const std::string &change);

    /**
     * Set the declared entry @p path ("Subsection/.../Name") to @p value,
     * or throw InputError naming the parameter, the value, what is allowed
     * and @p origin (where the value comes from).
     */
    void
    set_value(const std::string &path,
              const std::string &value,
              const std::string &origin);

    /// The index in experiment_types() of the one Experiment names.
    unsigned int
    chosen() const;

    /// Check the model's parameters and the chosen experiment's own.
    void
    validate() const;

    ParameterHandler         prm;
    std::vector<std::string> warnings; ///< read_warnings()
    /// The default is the registry's first.
    std::string experiment = experiment_types().front().name;
    Parameters  parameters;
    /// Each experiment's own parameters, in registry order (null: none).
    std::vector<std::unique_ptr<ExperimentParameters>> own;
  };
} // namespace rbc_ifem

#endif

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/input_files.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/parameter_names.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/experiments/cell_flow_experiment.h>
#include <rbc_ifem/experiments/diffusion_experiment.h>
#include <rbc_ifem/experiments/finite_uptake_experiment.h>
#include <rbc_ifem/experiments/flow_experiment.h>
#include <rbc_ifem/experiments/flowing_layouts_experiment.h>
#include <rbc_ifem/experiments/geometry_experiment.h>
#include <rbc_ifem/experiments/layouts_experiment.h>
#include <rbc_ifem/experiments/mesh_convergence_experiment.h>
#include <rbc_ifem/experiments/registry.h>
#include <rbc_ifem/experiments/shear_experiment.h>
#include <rbc_ifem/experiments/stretching_experiment.h>
#include <rbc_ifem/experiments/transit_experiment.h>

#include <deal.II/base/exceptions.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// The registry entry of an experiment without a subsection of its own.
    template <typename ExperimentClass>
    ExperimentType
    entry(const std::string &name, const std::string &documentation)
    {
      return {name,
              documentation,
              nullptr,
              [](const ExperimentContext &context,
                 const ExperimentParameters *) {
                return std::make_unique<ExperimentClass>(context);
              }};
    }

    /// The entry of an experiment with the subsection OwnParameters.
    template <typename ExperimentClass, typename OwnParameters>
    ExperimentType
    entry_with(const std::string &name, const std::string &documentation)
    {
      return {name,
              documentation,
              [] { return std::make_unique<OwnParameters>(); },
              [](const ExperimentContext    &context,
                 const ExperimentParameters *own) {
                return std::make_unique<ExperimentClass>(
                  context, static_cast<const OwnParameters &>(*own));
              }};
    }

    /// "flow" is the plasma alone, or with the immersed cells.
    std::unique_ptr<Experiment>
    create_flow(const ExperimentContext &context, const ExperimentParameters *)
    {
      if (context.parameters.immersed.enabled)
        return std::make_unique<CellFlowExperiment>(context);
      return std::make_unique<FlowExperiment>(context);
    }
  } // namespace

  const std::vector<ExperimentType> &
  experiment_types()
  {
    static const std::vector<ExperimentType> types{
      entry<GeometryExperiment>(
        "geometry",
        "build the fluid and diffusion meshes and the cell layout, and "
        "write them out."),
      entry<DiffusionExperiment>(
        "diffusion",
        "steady CO uptake of the layout (dm.csv, VTU of P and of the "
        "membrane flux)."),
      entry<LayoutsExperiment>(
        "layouts",
        "DM for every kind and number of cells of subsection Layout study "
        "(layouts.csv)."),
      entry_with<FiniteUptakeExperiment, FiniteUptakeParameters>(
        "finite uptake",
        "DM and DL, with CO bound inside the cells at the rates θ_CO of "
        "subsection Finite uptake, for every layout of subsection Layout "
        "study, beside Roughton and Forster's lumped estimate "
        "(uptake.csv)."),
      entry_with<MeshConvergenceExperiment, MeshConvergenceParameters>(
        "mesh convergence",
        "DM of the layout on successively finer meshes (convergence.csv)."),
      {"flow",
       "the plasma flow in the capillary for Time/Number of steps (flow.csv, "
       "VTU of v and p), with the cells of subsection Layout in it if "
       "Immersed cells/Enabled (cells.csv, dm.csv, VTU of the membranes).",
       nullptr,
       create_flow},
      entry_with<FlowingLayoutsExperiment, FlowingLayoutsParameters>(
        "flowing layouts",
        "every layout of subsection Layout study carried by the plasma "
        "(as flow with Immersed cells/Enabled), DM tracked over time: a "
        "flowing run per layout in <kind>_<n>_<seed>/, "
        "flowing_layouts.csv, flowing_layouts_summary.csv."),
      entry_with<StretchingExperiment, StretchingParameters>(
        "stretching",
        "one cell pulled by two beads with forces up to Stretching/Maximum "
        "force (stretch.csv, VTU of each equilibrium)."),
      entry_with<ShearExperiment, ShearParameters>(
        "shear",
        "a spherical capsule in simple shear for each Shear/Capillary "
        "numbers (shear.csv per run, shear_summary.csv)."),
      entry_with<TransitExperiment, TransitParameters>(
        "transit",
        "O2 loading of the cells of subsection Layout over a capillary "
        "transit of Transit/Duration, O2 and hemoglobin of subsection "
        "Oxygen (o2.csv, o2_balance.csv, o2_summary.csv, VTU of P and S).")};
    return types;
  }

  void
  ExperimentParameters::validate(const Parameters &) const
  {}

  std::string
  exact_text(const double value)
  {
    char       text[32];
    const auto end = std::to_chars(text, text + sizeof(text), value).ptr;
    return std::string(text, end);
  }

  RunParameters::RunParameters()
  {
    std::vector<std::string> names;
    std::string              documentation = "What to run.";
    for (const ExperimentType &type : experiment_types())
      {
        names.push_back(type.name);
        documentation += " " + type.name + ": " + type.documentation;
      }
    add_parameter(prm,
                  "Experiment",
                  experiment,
                  documentation,
                  Patterns::Selection(join_names(names)));
    parameters.add_parameters(prm);
    for (const ExperimentType &type : experiment_types())
      {
        own.push_back(type.make_parameters ? type.make_parameters() : nullptr);
        if (own.back())
          own.back()->add_parameters(prm);
      }
  }

  void
  RunParameters::read(const std::string              &filename,
                      const std::vector<std::string> &changes)
  {
    if (!std::filesystem::is_regular_file(filename) || !std::ifstream(filename))
      throw InputError("cannot read the parameter file '" + filename +
                       "': it does not exist or is not a readable file.");
    const std::string text = read_parameter_file(filename, warnings);
    check_parameter_names(text, filename, parameter_patterns(prm));
    // Each value against its pattern first: deal.II's own message names
    // neither the subsection nor what is allowed in words.
    for (const ParameterEntry &entry : parameter_entries(text))
      set_value(entry.path,
                entry.value,
                filename + ", line " + std::to_string(entry.line));
    try
      {
        std::istringstream lines(text);
        prm.parse_input(lines, filename);
      }
    catch (const ExceptionBase &e)
      {
        // deal.II's message names the line, the entry, the value and the
        // pattern; drop the backtrace and point to the list of names.
        std::ostringstream message;
        e.print_info(message);
        throw InputError("in parameter file '" + filename + "':\n" +
                         message.str() +
                         "\nRun 'rbc-ifem --print-parameters' for every "
                         "parameter, its allowed values and its default.");
      }
    resolve_file_parameters(
      prm, std::filesystem::path(filename).parent_path().string());
    for (const std::string &change : changes)
      set(change);
    validate();
  }

  void
  RunParameters::set(const std::string &change)
  {
    const std::string option = "--set \"" + change + "\"";
    const std::size_t equals = change.find('=');
    if (equals == std::string::npos)
      throw InputError(option + ": expected \"Subsection/Name=value\", such "
                                "as \"Time/Number of steps=10\".");
    const std::string path     = Utilities::trim(change.substr(0, equals));
    const std::string value    = Utilities::trim(change.substr(equals + 1));
    const auto        patterns = parameter_patterns(prm);
    if (patterns.count(path) == 0)
      throw InputError(option + ": there is no parameter '" + path + "'." +
                       suggest_parameter(path, patterns) +
                       " Run 'rbc-ifem --print-parameters' for every "
                       "parameter, as Subsection/Name.");
    set_value(path, value, "from " + option);
  }

  void
  RunParameters::set_value(const std::string &path,
                           const std::string &value,
                           const std::string &origin)
  {
    try
      {
        set_entry(prm, path, value);
      }
    catch (const ExceptionBase &)
      {
        throw InputError(path,
                         value,
                         allowed_values(parameter_patterns(prm).at(path)) +
                           " (" + origin + ").");
      }
  }

  void
  RunParameters::derive(const std::string                  &text,
                        const std::vector<ParameterChange> &changes)
  {
    prm.parse_input_from_string(text);
    for (const ParameterChange &change : changes)
      {
        if (!change.subsection.empty())
          prm.enter_subsection(change.subsection);
        prm.set(change.entry, change.value);
        if (!change.subsection.empty())
          prm.leave_subsection();
      }
    validate();
  }

  unsigned int
  RunParameters::chosen() const
  {
    const std::vector<ExperimentType> &types = experiment_types();
    for (unsigned int t = 0; t < types.size(); ++t)
      if (types[t].name == experiment)
        return t;
    // The Selection pattern of Experiment admits only the registry's names.
    AssertThrow(false, ExcInternalError());
    return 0;
  }

  void
  RunParameters::validate() const
  {
    check_magnitudes(prm);
    parameters.validate();
    if (const ExperimentParameters *own_parameters = own[chosen()].get())
      own_parameters->validate(parameters);
  }

  std::unique_ptr<Experiment>
  RunParameters::create_experiment(const MPI_Comm    communicator,
                                   const RunOptions &options) const
  {
    const unsigned int t = chosen();
    return experiment_types()[t].create(
      {experiment_types()[t].name, parameters, prm, communicator, options},
      own[t].get());
  }

  const std::vector<std::string> &
  RunParameters::read_warnings() const
  {
    return warnings;
  }

  const Parameters &
  RunParameters::model() const
  {
    return parameters;
  }

  const ParameterHandler &
  RunParameters::handler() const
  {
    return prm;
  }

  void
  RunParameters::print(std::ostream &out) const
  {
    out << parameter_text(prm);
  }
} // namespace rbc_ifem

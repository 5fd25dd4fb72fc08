#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/experiments/cell_flow_experiment.h>

namespace rbc_ifem
{
  CellFlowExperiment::CellFlowExperiment(const ExperimentContext &context)
    : Experiment(context, ParametersFile::before_work)
  {}

  void
  CellFlowExperiment::setup()
  {
    if (parameters.layout.kind != LayoutKind::file &&
        parameters.layout.n_cells == 0)
      throw InputError("Layout/Number of cells",
                       "0",
                       "a flow with Immersed cells/Enabled = true needs at "
                       "least one cell.");
    pcout << "  with immersed cells ("
          << name_of(parameters.fluid.model, fluid_model_names()) << ')'
          << std::endl;
    simulation =
      std::make_unique<IFEMSimulation>(parameters,
                                       parameter_file_text,
                                       FlowDomain::capillary(parameters),
                                       communicator,
                                       timer,
                                       options);
    simulation->setup();
  }

  void
  CellFlowExperiment::execute()
  {
    simulation->run();
  }
} // namespace rbc_ifem

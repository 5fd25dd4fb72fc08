#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/experiments/finite_uptake_experiment.h>
#include <rbc_ifem/experiments/registry.h>

#include <iomanip>
#include <numeric>
#include <utility>

namespace rbc_ifem
{
  void
  FiniteUptakeParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Finite uptake");
    add_selection(prm,
                  "Theta models",
                  theta_models,
                  theta_model_names(),
                  "Experiment 'finite uptake': the formulas θ_CO(PO₂) (as "
                  "Diffusion/Theta model describes them; not given) "
                  "evaluated at each of the Oxygen pressures.");
    add_parameter(prm,
                  "Oxygen pressures",
                  oxygen_pressures,
                  "Experiment 'finite uptake': the PO₂ values [Torr] at "
                  "which each of the Theta models gives a θ_CO that DL is "
                  "computed for; may be empty.",
                  Patterns::List(Patterns::Double(0.), 0));
    add_parameter(prm,
                  "Thetas",
                  thetas,
                  "Experiment 'finite uptake': θ_CO values given directly "
                  "[mL CO min⁻¹ Torr⁻¹ per mL of blood], computed after the "
                  "oxygen pressures'; may be empty.",
                  Patterns::List(GreaterThan(), 0));
    prm.leave_subsection();
  }

  void
  FiniteUptakeParameters::validate(const Parameters &parameters) const
  {
    const DiffusionParameters &d = parameters.diffusion;
    if (d.method != DiffusionMethod::cut_cell)
      throw InputError("Diffusion/Method",
                       "Lagrange multiplier",
                       "experiment 'finite uptake' puts the reaction inside "
                       "the cells, which needs cut cell.");
    for (const ThetaModel model : theta_models)
      if (model == ThetaModel::given)
        throw InputError("Finite uptake/Theta models",
                         "given",
                         "each entry is a formula θ(PO₂): Roughton-Forster "
                         "1957, Forster 1987 or Guenard 2016 (θ given "
                         "directly go in Finite uptake/Thetas).");
    if (oxygen_pressures.empty() && thetas.empty())
      throw InputError("Finite uptake/Thetas",
                       "",
                       "the sweep is empty: give Oxygen pressures, Thetas "
                       "or both.");
  }

  FiniteUptakeExperiment::FiniteUptakeExperiment(
    const ExperimentContext      &context,
    const FiniteUptakeParameters &sweep)
    : UptakeExperiment(context)
    , sweep(sweep)
  {}

  void
  FiniteUptakeExperiment::setup()
  {
    // One cell is one layout, whatever the kind.
    bool one_cell = false;
    for (const auto &samples :
         parameters.layout_study.layouts(parameters.layout))
      for (const LayoutParameters &layout : samples)
        if (layout.n_cells > 1 || !std::exchange(one_cell, true))
          layouts.push_back(std::make_unique<const PlacedCells>(
            study_layout(layout, parameters.geometry, parameters.cells),
            parameters.geometry,
            parameters.cells,
            parameters.cells.surface_refinements));
  }

  std::vector<FiniteUptakeExperiment::Theta>
  FiniteUptakeExperiment::thetas() const
  {
    std::vector<Theta>  thetas;
    DiffusionParameters d = parameters.diffusion;
    for (const ThetaModel model : sweep.theta_models)
      for (const double pressure : sweep.oxygen_pressures)
        {
          d.theta_model     = model;
          d.oxygen_pressure = pressure;
          thetas.push_back({name_of(model, theta_model_names()),
                            exact_text(pressure),
                            d.theta_blood()});
        }
    for (const double theta : sweep.thetas)
      thetas.push_back({"given", "", theta});
    return thetas;
  }

  void
  FiniteUptakeExperiment::execute()
  {
    const std::vector<Theta> sweep_thetas = thetas();
    // θ per mL of blood → the cytoplasm's binding rate k, as the solver
    // takes it (DiffusionParameters::reaction_rate()).
    std::vector<double> rates;
    DiffusionParameters d = parameters.diffusion;
    d.theta_model         = ThetaModel::given;
    for (const Theta &theta : sweep_thetas)
      {
        d.theta = theta.value;
        rates.push_back(d.reaction_rate());
      }

    CsvTable table("layout,n_cells,seed,cells_volume,theta_source,"
                   "oxygen_pressure,theta,dm_total,dl_total,"
                   "roughton_forster_dl,roughton_forster_error,"
                   "dl_iterations");
    for (const auto &cells : layouts)
      {
        const std::vector<double> &volumes = cells->membranes.volumes();
        const double               volume =
          std::accumulate(volumes.begin(), volumes.end(), 0.);
        const std::vector<Uptake> uptakes =
          uptake.solve_for_rates(cells->membranes.membrane_surfaces(), rates);
        const LayoutParameters &layout = cells->layout.parameters();
        Uptake                  sink   = uptakes.front();
        sink.dl_cells.clear();
        report(cells->layout.description() + ", membrane sink", sink);
        for (unsigned int i = 0; i < uptakes.size(); ++i)
          {
            const Uptake &uptake = uptakes[i];
            const Theta  &theta  = sweep_thetas[i];
            // 1/DL = 1/DM + 1/(θ V_c): θ V_c = k V in µm³ s⁻¹ Torr⁻¹.
            const double lumped =
              1. / (1. / uptake.dm_total + 1. / (rates[i] * volume));
            pcout << "    θ " << std::setprecision(4) << theta.value << " ("
                  << theta.source
                  << (theta.oxygen_pressure.empty() ?
                        "" :
                        ", PO₂ " + theta.oxygen_pressure + " Torr")
                  << "): DL " << std::setprecision(6) << uptake.dl_total
                  << " µm³/(s Torr), " << uptake.dl_iterations
                  << " iterations, " << std::setprecision(3) << uptake.seconds
                  << " s; Roughton-Forster " << std::setprecision(6) << lumped
                  << " (" << std::showpos << std::setprecision(3)
                  << 100. * (lumped / uptake.dl_total - 1.) << std::noshowpos
                  << "%)" << std::endl;
            table.add(name_of(layout.kind, layout_kind_names()),
                      layout.n_cells,
                      layout.seed,
                      volume,
                      theta.source,
                      theta.oxygen_pressure,
                      theta.value,
                      uptake.dm_total,
                      uptake.dl_total,
                      lumped,
                      lumped / uptake.dl_total - 1.,
                      uptake.dl_iterations);
          }
      }
    create_output_directory(parameters.output_directory, communicator);
    write_on_rank_0(communicator, [&]() {
      table.write(parameters.output_directory + "/uptake.csv");
    });
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/time_step_limit.h>
#include <rbc_ifem/experiments/derived_flow_run.h>
#include <rbc_ifem/experiments/registry.h>
#include <rbc_ifem/experiments/shear_experiment.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/run_observer.h>

#include <deal.II/base/patterns.h>
#include <deal.II/base/timer.h>

#include <cmath>
#include <limits>

namespace rbc_ifem
{
  void
  ShearParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Shear");
    add_parameter(prm,
                  "Shear rate",
                  shear_rate,
                  "Experiment 'shear': the rate γ̇ of the simple shear "
                  "v = (γ̇ y, 0, 0) the box walls impose [1/s]. Results "
                  "depend on it only through the capillary number.",
                  GreaterThan());
    add_parameter(prm,
                  "Capillary numbers",
                  capillary_numbers,
                  "One run per Ca = μ a γ̇ / G, a the capsule radius "
                  "(Cells/Diameter / 2) and G the membrane's shear "
                  "modulus: every modulus of subsection Membrane is "
                  "scaled by the same factor to give this G, so their "
                  "ratios are kept.",
                  Patterns::List(GreaterThan(), 1));
    add_parameter(prm,
                  "Box size",
                  box,
                  "Length (x, the flow direction; the ends x = ±L/2 are "
                  "open), height (y, between the moving walls) and width "
                  "(z, walls moving with the shear) of the box, centred "
                  "on the capsule [µm]. Each must be a multiple of "
                  "Cells/Diameter, the coarse mesh's cell size.",
                  Patterns::List(GreaterThan(), 3, 3, ","));
    add_parameter(prm,
                  "Total strain",
                  strain,
                  "Each run lasts until γ̇ t reaches this.",
                  GreaterThan());
    add_parameter(prm,
                  "Averaging strain",
                  averaging_strain,
                  "The steady deformation is the mean over the steadiest "
                  "window of this length in γ̇ t: the one over which D "
                  "changes least. Without bending stiffness the membrane "
                  "of a capsule at small Ca wrinkles late in a run and D "
                  "creeps up (doc/validation.md); the window finds the "
                  "plateau before that.",
                  GreaterThan());
    add_parameter(prm,
                  "Output strain interval",
                  output_strain,
                  "A shear.csv row, a cells.csv row and the VTU files "
                  "every γ̇ t of this length.",
                  GreaterThan());
    add_parameter(prm,
                  "Time step fraction",
                  time_step_fraction,
                  "Δt of each run as a fraction of its explicit-coupling "
                  "time step limit (doc/ifem.md), which scales with 1/G: "
                  "small Ca take more steps. Time/Time step is not used.",
                  GreaterThan(0., 1.));
    prm.leave_subsection();
  }

  void
  ShearParameters::validate(const Parameters &parameters) const
  {
    const CellParameters &cells = parameters.cells;
    if (!(averaging_strain < strain))
      throw InputError("Shear/Averaging strain",
                       to_text(averaging_strain),
                       "it must be below Shear/Total strain = " +
                         to_text(strain) + ".");
    const char *names[] = {"length", "height", "width"};
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double cells_across = box[d] / cells.diameter;
        if (!(cells_across >= 2. &&
              std::abs(cells_across - std::round(cells_across)) < 1e-6))
          throw InputError("Shear/Box size",
                           to_text(box[0]) + ", " + to_text(box[1]) + ", " +
                             to_text(box[2]),
                           std::string("the box ") + names[d] +
                             " must be a multiple of Cells/Diameter = " +
                             to_text(cells.diameter) +
                             " µm, at least twice it, so that the capsule "
                             "fits.");
      }
  }

  namespace
  {
    /**
     * The capsule's Taylor deformation and inclination over a run: shear.csv
     * (time,taylor_deformation,inclination_over_pi), the progress line's
     * Taylor deformation, and the history steady_state() reads.
     */
    class TaylorDeformationHistory : public RunObserver
    {
    public:
      void
      record(const double time, const std::vector<CellShape> &shapes) override
      {
        history.push_back(
          {{time, shapes[0].taylor_deformation, shapes[0].inclination}});
      }

      std::string
      progress(const std::vector<CellShape> &shapes) const override
      {
        return ", Taylor deformation " + to_text(shapes[0].taylor_deformation);
      }

      void
      write_tables(const std::string &directory) const override
      {
        CsvTable table("time,taylor_deformation,inclination_over_pi");
        for (const auto &[time, deformation, inclination] : history)
          table.add(time, deformation, inclination / numbers::PI);
        table.write(directory + "/shear.csv");
      }

      std::string
      state() const override
      {
        std::vector<double> values;
        for (const std::array<double, 3> &sample : history)
          values.insert(values.end(), sample.begin(), sample.end());
        return packed(values);
      }

      void
      restore(const std::string &state) override
      {
        const std::vector<double> values = unpacked(state);
        history.clear();
        for (std::size_t i = 0; i + 2 < values.size(); i += 3)
          history.push_back({{values[i], values[i + 1], values[i + 2]}});
      }

      /// Time [s], Taylor deformation, inclination [rad] of every record.
      std::vector<std::array<double, 3>> history;
    };
  } // namespace

  ShearExperiment::ShearExperiment(const ExperimentContext &context,
                                   const ShearParameters   &shear)
    : Experiment(context, ParametersFile::before_work)
    , shear(shear)
  {}

  ShearExperiment::~ShearExperiment() = default;

  void
  ShearExperiment::setup()
  {
    pcout << "  a spherical capsule of radius "
          << parameters.cells.diameter / 2. << " µm ("
          << parameters.membrane.law
          << ") in simple shear γ̇ = " << shear.shear_rate << " 1/s, box "
          << shear.box[0] << " x " << shear.box[1] << " x " << shear.box[2]
          << " µm, " << shear.capillary_numbers.size()
          << " capillary number(s), to γ̇ t = " << shear.strain << std::endl;
    // The capsule's mesh and the fluid mesh around it do not depend on Ca:
    // the box's coarse cells have the capsule's diameter as edge, halved by
    // every global and band refinement.
    point_spacing = CellPopulation(FlowDomain::shear_box(shear.box,
                                                         shear.shear_rate,
                                                         parameters)
                                     .placements,
                                   parameters.cells,
                                   parameters.membrane)
                      .point_spacing();
    mesh_size = parameters.cells.diameter /
                std::pow(2.,
                         parameters.mesh.fluid_global_refinements +
                           parameters.mesh.fluid_band_refinements);
    for (const double capillary_number : shear.capillary_numbers)
      runs.push_back(derive_run(capillary_number));
  }

  std::unique_ptr<RunParameters>
  ShearExperiment::derive_run(const double capillary_number) const
  {
    MembraneParameters membrane = parameters.membrane;
    const double       factor   = parameters.fluid.viscosity *
                          parameters.cells.diameter / 2. * shear.shear_rate /
                          (capillary_number * membrane.shear_modulus);
    for (double *modulus : {&membrane.shear_modulus,
                            &membrane.area_dilation_modulus,
                            &membrane.bending_modulus,
                            &membrane.area_penalty,
                            &membrane.volume_penalty})
      *modulus *= factor;

    // Whole steps to the total strain, each within the fraction of the limit.
    const CouplingTimeStepLimit limit(parameters.fluid.viscosity,
                                      membrane,
                                      point_spacing,
                                      mesh_size);
    const double                largest_strain_step =
      shear.time_step_fraction * limit.limit * shear.shear_rate;
    const unsigned int n_steps =
      static_cast<unsigned int>(std::ceil(shear.strain / largest_strain_step));
    const double time_step       = shear.strain / shear.shear_rate / n_steps;
    const long   output_interval = std::max(
      1l, std::lround(shear.output_strain / (shear.shear_rate * time_step)));

    const std::string directory =
      parameters.output_directory + "/ca_" + csv_row(capillary_number);
    std::vector<ParameterChange> changes{
      {"", "Output directory", directory},
      {"Membrane", "Shear modulus", exact_text(membrane.shear_modulus)},
      {"Membrane",
       "Area dilation modulus",
       exact_text(membrane.area_dilation_modulus)},
      {"Membrane", "Bending modulus", exact_text(membrane.bending_modulus)},
      {"Membrane", "Area penalty", exact_text(membrane.area_penalty)},
      {"Membrane", "Volume penalty", exact_text(membrane.volume_penalty)},
      {"Time", "Time step", exact_text(time_step)},
      {"Time", "Number of steps", std::to_string(n_steps)},
      {"Time", "Output interval", std::to_string(output_interval)},
      {"Immersed cells", "Enabled", "true"},
      {"Immersed cells", "Follow cells", "false"},
      {"Immersed cells", "Diffusion interval", "0"},

      {"Immersed cells", "Progress interval", std::to_string(output_interval)},
      {"Fluid", "Frame velocity", "0"},
      // The run's parameters.prm reruns this one run (in its own ca_<Ca>/):
      // its moduli give this capillary number with a scale factor of 1.
      {"Shear", "Capillary numbers", exact_text(capillary_number)}};
    for (const ParameterChange &change :
         resumable_run(parameters, directory, n_steps))
      changes.push_back(change);
    auto run = std::make_unique<RunParameters>();
    run->derive(parameter_file_text, changes);
    return run;
  }

  ShearSummary
  ShearExperiment::steady_state(
    const std::vector<std::array<double, 3>> &history) const
  {
    // The samples are one output interval apart (the last one may be
    // closer); a window holds the samples spanning Averaging strain.
    const double       rate    = shear.shear_rate;
    const double       spacing = rate * (history[1][0] - history[0][0]);
    const unsigned int n_window =
      std::min<unsigned int>(history.size(),
                             std::lround(shear.averaging_strain / spacing) + 1);
    ShearSummary best;
    double       least_change = std::numeric_limits<double>::infinity();
    for (unsigned int first = 0; first + n_window <= history.size(); ++first)
      {
        double low = history[first][1], high = low, deformation = 0.,
               inclination = 0.;
        for (unsigned int i = first; i < first + n_window; ++i)
          {
            low  = std::min(low, history[i][1]);
            high = std::max(high, history[i][1]);
            deformation += history[i][1];
            inclination += history[i][2] / numbers::PI;
          }
        if (high - low < least_change)
          {
            least_change            = high - low;
            best.steady_deformation = deformation / n_window;
            best.steady_inclination = inclination / n_window;
            best.steady_from        = rate * history[first][0];
            best.steady_to          = rate * history[first + n_window - 1][0];
          }
      }
    return best;
  }

  ShearSummary
  ShearExperiment::run_one(const double         capillary_number,
                           const RunParameters &run)
  {
    const Parameters &p = run.model();
    pcout << "\nCa = " << capillary_number
          << ": G = " << p.membrane.shear_modulus
          << " pN/µm, Δt = " << p.time.time_step
          << " s (γ̇ Δt = " << shear.shear_rate * p.time.time_step << "), "
          << p.time.n_steps << " steps, in " << p.output_directory << std::endl;
    Timer                    clock;
    TaylorDeformationHistory deformation;
    run_derived_flow(run,
                     FlowDomain::shear_box(shear.box, shear.shear_rate, p),
                     deformation,
                     communicator,
                     pcout,
                     options);

    ShearSummary summary     = steady_state(deformation.history);
    summary.capillary_number = capillary_number;
    summary.time_step        = p.time.time_step;
    summary.n_steps          = p.time.n_steps;
    summary.wall_seconds     = clock.wall_time();
    pcout << "Ca = " << capillary_number << ": steady Taylor deformation "
          << summary.steady_deformation << ", inclination "
          << summary.steady_inclination
          << " π (means over γ̇ t = " << summary.steady_from << " to "
          << summary.steady_to << ", where D changes least)" << std::endl;
    return summary;
  }

  void
  ShearExperiment::execute()
  {
    CsvTable summaries(
      "capillary_number,steady_deformation,steady_inclination_over_pi,"
      "steady_from_strain,steady_to_strain,time_step,n_steps,wall_seconds");
    for (unsigned int r = 0; r < runs.size(); ++r)
      {
        const double       ca = shear.capillary_numbers[r];
        TimerOutput::Scope scope(timer, "Ca = " + csv_row(ca));
        const ShearSummary s = run_one(ca, *runs[r]);
        summaries.add(s.capillary_number,
                      s.steady_deformation,
                      s.steady_inclination,
                      s.steady_from,
                      s.steady_to,
                      s.time_step,
                      s.n_steps,
                      s.wall_seconds);
        write_on_rank_0(communicator, [&]() {
          summaries.write(parameters.output_directory + "/shear_summary.csv");
        });
      }
  }
} // namespace rbc_ifem

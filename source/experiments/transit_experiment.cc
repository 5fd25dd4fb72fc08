#include <rbc_ifem/base/csv.h>
#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/base/solver_failure.h>
#include <rbc_ifem/diffusion/bdf2.h>
#include <rbc_ifem/diffusion/cut_cell_oxygen.h>
#include <rbc_ifem/diffusion/step_control.h>
#include <rbc_ifem/diffusion/uptake.h>
#include <rbc_ifem/diffusion/uptake_mesh.h>
#include <rbc_ifem/experiments/registry.h>
#include <rbc_ifem/experiments/transit_experiment.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/timer.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

namespace rbc_ifem
{
  void
  TransitParameters::add_parameters(ParameterHandler &prm)
  {
    oxygen.add_parameters(prm);
    prm.enter_subsection("Transit");
    add_parameter(prm,
                  "Duration",
                  duration,
                  "Experiment 'transit': how long the cells are followed "
                  "[s]: the capillary transit time, about 0.75 at rest and "
                  "0.25-0.3 in heavy exercise.",
                  GreaterThan());
    add_parameter(prm,
                  "Cells flow",
                  cells_flow,
                  "Experiment 'transit': true, the cells are carried by the "
                  "plasma and deform (not built yet: the run stops with an "
                  "error); false, they are held rigid where the layout puts "
                  "them, in plasma at rest.");
    add_parameter(prm,
                  "Time step",
                  time_step,
                  "Experiment 'transit': the step of the O2 transport [s] "
                  "(BDF2, the binding implicit); made a little shorter if "
                  "it does not divide the Duration. With a Time step "
                  "tolerance, the first step.",
                  GreaterThan());
    add_parameter(prm,
                  "Time step tolerance",
                  time_step_tolerance,
                  "Experiment 'transit': 0, every step is the Time step; "
                  "otherwise each step's length is chosen so that its "
                  "estimated local error, the root mean square over the "
                  "DoFs of P's relative to the Alveolar PO2 and of S's, is "
                  "at most this (a step above it is done again shorter), "
                  "and no step is longer than the Output interval; a step "
                  "whose Newton method or GMRES fails is done again at a "
                  "fifth (three failures in a row stop the run).",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Output interval",
                  output_interval,
                  "Experiment 'transit': the rows of o2.csv and "
                  "o2_balance.csv and the VTU of P and S every this long "
                  "[s] (rounded to whole steps; at least one step), and at "
                  "the end.",
                  GreaterThan());
    prm.leave_subsection();
  }

  void
  TransitParameters::validate(const Parameters &parameters) const
  {
    if (parameters.diffusion.method != DiffusionMethod::cut_cell)
      throw InputError("Diffusion/Method",
                       "Lagrange multiplier",
                       "experiment 'transit' solves for O2 inside the cells, "
                       "which needs cut cell.");
    if (duration < time_step)
      throw InputError("Transit/Duration",
                       exact_text(duration),
                       "it must be at least one Transit/Time step (" +
                         exact_text(time_step) + " s).");
    if (cells_flow)
      throw InputError("Transit/Cells flow",
                       "true",
                       "flowing, deforming cells are not built yet in "
                       "experiment 'transit': set false to hold the cells "
                       "rigid where the layout puts them.");
  }

  namespace
  {
    /// Each cell's time to 95% of its rise to the equilibrium saturation,
    /// from the rows of o2.csv as they come.
    class RiseTimes
    {
    public:
      RiseTimes(const std::vector<double> &start, const double target)
        : start(start)
        , target(target)
        , times(start.size())
        , last(start)
      {}

      /// The cells' saturations @p saturations at @p time; a crossing
      /// between the last time and this one by linear interpolation.
      void
      add(const double time, const std::vector<double> &saturations)
      {
        // A cell already at the target (P_v = P_A) has no rise to time.
        for (unsigned int c = 0; c < start.size(); ++c)
          {
            const double rise  = std::abs(saturations[c] - start[c]),
                         was   = std::abs(last[c] - start[c]),
                         wants = 0.95 * std::abs(target - start[c]);
            if (!times[c] && wants > 1e-12 && rise >= wants)
              times[c] =
                last_time + (time - last_time) * (wants - was) / (rise - was);
          }
        last      = saturations;
        last_time = time;
      }

      /// The time of cell @p c, empty if it has not risen so far.
      std::string
      text(const unsigned int c) const
      {
        return times[c] ? exact_text(*times[c]) : "";
      }

    private:
      const std::vector<double>          start;
      const double                       target;
      std::vector<std::optional<double>> times;
      std::vector<double>                last;
      double                             last_time = 0.;
    };

    /**
     * @p o2's estimate of the local error of a step of @p step [s]
     * (CutCellOxygen::try_step()). With steps to a tolerance (@p adaptive),
     * a step whose Newton method or GMRES fails counts as too long: its
     * error is infinite, and StepControl tries it again at a fifth, as a
     * stiff start may need. The third failure in a row stops the run with
     * its own message (shorter steps did not help), as the first does with
     * fixed steps. @p failures counts the failures in a row.
     */
    double
    try_step(CutCellOxygen            &o2,
             const double              step,
             const bool                adaptive,
             unsigned int             &failures,
             const ConditionalOStream &pcout)
    {
      try
        {
          const double error = o2.try_step(step);
          failures           = 0;
          return error;
        }
      catch (const SolverFailure &failure)
        {
          if (!adaptive || ++failures == 3)
            throw;
          pcout << "  t = " << std::setprecision(4) << o2.time()
                << " s: a step of " << std::setprecision(3) << step
                << " s failed (" << failure.what() << "); shorter" << std::endl;
          return std::numeric_limits<double>::infinity();
        }
    }
  } // namespace

  TransitExperiment::TransitExperiment(const ExperimentContext &context,
                                       const TransitParameters &transit)
    : Experiment(context, ParametersFile::before_work)
    , transit(transit)
  {}

  void
  TransitExperiment::setup()
  {
    cells =
      std::make_unique<const PlacedCells>(parameters.layout,
                                          parameters.geometry,
                                          parameters.cells,
                                          parameters.cells.surface_refinements);
  }

  void
  TransitExperiment::execute()
  {
    const std::string &directory = parameters.output_directory;
    UptakeMesh         mesh(parameters.geometry,
                    parameters.mesh,
                    DiffusionMethod::cut_cell,
                    communicator,
                    timer);
    const auto         geometry =
      build_cut_cell_geometry(mesh,
                              parameters.geometry,
                              cells->membranes.membrane_surfaces(),
                              parameters.diffusion.degree,
                              true,
                              timer);
    const HillBinding binding = transit.oxygen.binding();
    CutCellOxygen     o2(*geometry,
                     parameters.diffusion,
                     transit.oxygen,
                     binding,
                     DiffusionBoundary::alveolar_surface,
                     timer);
    o2.assemble();
    o2.start(transit.oxygen.venous_pressure);

    // Whole steps: the step shortened to divide the duration, the outputs
    // every whole number of them (with a tolerance, the steps then vary
    // between the outputs).
    const unsigned int n_steps = static_cast<unsigned int>(
      std::ceil(transit.duration / transit.time_step - 1e-9));
    const double time_step = transit.duration / n_steps;
    const double output_period =
      time_step * std::max(1., std::round(transit.output_interval / time_step));
    StepControl steps(time_step, transit.time_step_tolerance, output_period);
    pcout << "Transit: " << cells->membranes.size() << " cells, " << o2.n_dofs()
          << " DoFs, steps of " << time_step << " s"
          << (transit.time_step_tolerance > 0. ?
                " at first, then to a local error of " +
                  exact_text(transit.time_step_tolerance) :
                std::string())
          << ", P_A " << transit.oxygen.alveolar_pressure << " Torr, P_v "
          << transit.oxygen.venous_pressure << " Torr" << std::endl;

    CsvTable o2_table("time,cell,saturation,mean_po2,uptake_rate");
    CsvTable balance("time,dissolved,bound,wall_oxygen,balance_error");
    const CutCellOxygen::Amounts start_amounts = o2.amounts();
    const double start_total = start_amounts.dissolved + start_amounts.bound;
    std::vector<CutCellOxygen::CellState> states = o2.cell_states();
    std::vector<double>                   start_saturation;
    for (const auto &state : states)
      start_saturation.push_back(state.saturation);
    RiseTimes rise(start_saturation,
                   binding.equilibrium_saturation(
                     transit.oxygen.alveolar_pressure));
    // The O2 per cell at the last two steps, for the uptake rates (BDF2's
    // derivative, as the scheme's own).
    std::vector<double> oxygen(states.size()), older(states.size()),
      rates(states.size());
    for (unsigned int c = 0; c < states.size(); ++c)
      oxygen[c] = older[c] = states[c].oxygen;

    UptakeFields fields("o2");
    create_output_directory(directory, communicator);
    write_on_rank_0(communicator, [&]() {
      cells->membranes.table().write(directory + "/cells.csv");
    });
    Timer        clock;
    unsigned int n_outputs = 0, n_accepted = 0, failures = 0;
    double       last_step = 0., step = 0., last_line = 0.;
    // The end of a progress line: the step, and the time left at its pace;
    // notes when the last line was printed.
    const auto pace = [&]() {
      std::ostringstream text;
      text << "step " << std::setprecision(3) << step << " s "
           << time_left_text(clock.wall_time(),
                             n_accepted,
                             static_cast<unsigned int>(std::ceil(
                               (transit.duration - o2.time()) / step)));
      last_line = clock.wall_time();
      return text.str();
    };
    for (const double stop : output_times(transit.duration, output_period))
      {
        while (o2.time() < stop - 1e-9 * output_period)
          {
            step = steps.next(o2.time(), stop);
            if (!steps.judge(try_step(
                  o2, step, transit.time_step_tolerance > 0., failures, pcout)))
              continue;
            o2.accept_step();
            ++n_accepted;
            states = o2.cell_states();
            const Bdf2          bdf(step, last_step);
            std::vector<double> saturations;
            for (unsigned int c = 0; c < states.size(); ++c)
              {
                const double now = states[c].oxygen;
                rates[c]  = bdf.derivative(now, oxygen[c], older[c], step);
                older[c]  = oxygen[c];
                oxygen[c] = now;
                saturations.push_back(states[c].saturation);
              }
            last_step = step;
            rise.add(o2.time(), saturations);
            // Between outputs far apart, a line at least every minute.
            if (clock.wall_time() > last_line + 60. &&
                o2.time() < stop - 1e-9 * output_period)
              pcout << "  t = " << std::setprecision(4) << o2.time()
                    << " s: " << pace() << std::endl;
          }

        const CutCellOxygen::Amounts amounts = o2.amounts();
        const double change = amounts.dissolved + amounts.bound - start_total;
        // Relative to the larger of what entered and what the mesh held at
        // the start: what entered is zero when P_v = P_A.
        const double error = (change - o2.wall_oxygen()) /
                             std::max(std::abs(o2.wall_oxygen()), start_total);
        double mean_saturation = 0., volume = 0.;
        for (unsigned int c = 0; c < states.size(); ++c)
          {
            o2_table.add(
              o2.time(), c, states[c].saturation, states[c].pressure, rates[c]);
            mean_saturation += states[c].saturation * states[c].volume;
            volume += states[c].volume;
          }
        balance.add(
          o2.time(), amounts.dissolved, amounts.bound, o2.wall_oxygen(), error);
        o2.update_flux_map();
        fields.write(o2, directory, o2.time(), ++n_outputs, communicator);
        write_on_rank_0(communicator, [&]() {
          o2_table.write(directory + "/o2.csv");
          balance.write(directory + "/o2_balance.csv");
        });
        const auto [newton, gmres] = o2.last_iterations();
        pcout << "  t = " << std::setprecision(4) << o2.time() << " s: mean S "
              << std::setprecision(5) << mean_saturation / volume
              << ", O2 balance " << std::setprecision(2) << error << ", Newton "
              << newton << ", GMRES " << gmres << ", " << pace() << std::endl;
      }

    pcout << "Transit: " << n_accepted << " steps, " << steps.n_rejected()
          << " tried again shorter" << std::endl;

    CsvTable summary(
      "cell,start_saturation,end_saturation,end_mean_po2,time_to_95");
    for (unsigned int c = 0; c < states.size(); ++c)
      summary.add(c,
                  start_saturation[c],
                  states[c].saturation,
                  states[c].pressure,
                  rise.text(c));
    write_on_rank_0(communicator,
                    [&]() { summary.write(directory + "/o2_summary.csv"); });
  }
} // namespace rbc_ifem

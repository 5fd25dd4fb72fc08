#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/base/output_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/experiments/derived_flow_run.h>
#include <rbc_ifem/experiments/flowing_layouts_experiment.h>
#include <rbc_ifem/experiments/registry.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/run_observer.h>

#include <deal.II/base/patterns.h>
#include <deal.II/base/timer.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rbc_ifem
{
  void
  FlowingLayoutsParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Flowing layouts");
    add_parameter(prm,
                  "Steady window",
                  steady_window,
                  "Experiment 'flowing layouts': the steady DM of a run is "
                  "the mean of its DM solves in the last Steady window of "
                  "the run [s]; flowing_layouts_summary.csv gives their "
                  "spread (max - min) / mean, which says how steady it is.",
                  GreaterThan());
    prm.leave_subsection();
  }

  void
  FlowingLayoutsParameters::validate(const Parameters &parameters) const
  {
    if (parameters.immersed.diffusion_interval == 0 ||
        parameters.immersed.diffusion_interval > parameters.time.n_steps)
      throw InputError("Immersed cells/Diffusion interval",
                       std::to_string(parameters.immersed.diffusion_interval),
                       "the flowing layouts track DM: solve it every k steps, "
                       "1 <= k <= Time/Number of steps = " +
                         std::to_string(parameters.time.n_steps) + ".");
    if (parameters.time.automatic_time_step())
      throw InputError("Time/Time step",
                       "auto",
                       "the flowing layouts compare runs of the same "
                       "duration: give the step in seconds (the explicit-"
                       "coupling estimate of a flow run is a guide).");
    const double duration = parameters.time.n_steps * parameters.time.time_step;
    if (!(steady_window < duration))
      throw InputError("Flowing layouts/Steady window",
                       to_text(steady_window),
                       "it must be shorter than the run, Time/Number "
                       "of steps x Time/Time step = " +
                         to_text(duration) + " s.");
    if (!parameters.immersed.pushing_forces.empty())
      throw InputError("Immersed cells/Pushing forces",
                       parameters.immersed.pushing_forces,
                       "the flowing layouts vary the number of cells; "
                       "pushing forces name each cell, so leave it empty.");
  }

  namespace
  {
    /// A run's DM solves with the gaps then, and its cells' last shapes.
    class UptakeHistory : public RunObserver
    {
    public:
      void
      record(const double, const std::vector<CellShape> &shapes) override
      {
        mean_deformation = 0.;
        for (const CellShape &shape : shapes)
          mean_deformation += shape.deformation_index / shapes.size();
      }

      void
      record_uptake(const double  time,
                    const Uptake &uptake,
                    const double  smallest_gap) override
      {
        solves.push_back({time, uptake.dm_total, smallest_gap});
      }

      void
      write_tables(const std::string &) const override
      {}

      std::string
      state() const override
      {
        std::vector<double> values{mean_deformation};
        for (const FlowingLayoutResult::Solve &solve : solves)
          values.insert(values.end(),
                        {solve.time, solve.dm_total, solve.smallest_gap});
        return packed(values);
      }

      void
      restore(const std::string &state) override
      {
        const std::vector<double> values = unpacked(state);
        mean_deformation                 = values.at(0);
        solves.clear();
        for (std::size_t i = 1; i + 2 < values.size(); i += 3)
          solves.push_back({values[i], values[i + 1], values[i + 2]});
      }

      std::vector<FlowingLayoutResult::Solve> solves;
      double                                  mean_deformation = 0.;
    };

    /// The directory and file stem of a run: <kind>_<n>_<seed>.
    std::string
    run_name(const LayoutParameters &layout)
    {
      return name_of(layout.kind, layout_kind_names()) + "_" +
             std::to_string(layout.n_cells) + "_" + std::to_string(layout.seed);
    }

    /// The first of @p earlier layouts whose cells are exactly @p cells,
    /// or earlier.size() if none is.
    unsigned int
    first_alike(const std::vector<std::vector<CellPlacement>> &earlier,
                const std::vector<CellPlacement>              &cells)
    {
      const auto alike = [&](const std::vector<CellPlacement> &other) {
        return std::equal(cells.begin(),
                          cells.end(),
                          other.begin(),
                          other.end(),
                          [](const CellPlacement &a, const CellPlacement &b) {
                            return a.center == b.center && a.axis == b.axis;
                          });
      };
      return std::find_if(earlier.begin(), earlier.end(), alike) -
             earlier.begin();
    }

    /// "" for an infinite gap (one cell), the number otherwise.
    std::string
    gap_text(const double gap)
    {
      return std::isfinite(gap) ? csv_row(gap) : std::string();
    }
  } // namespace

  FlowingLayoutsExperiment::FlowingLayoutsExperiment(
    const ExperimentContext        &context,
    const FlowingLayoutsParameters &own)
    : Experiment(context, ParametersFile::before_work)
    , own(own)
    , history("layout,n_cells,seed,hematocrit,time,dm_total,dm_per_cell,"
              "min_gap")
    , summary("layout,n_cells,seed,hematocrit,static_dm_total,steady_dm_total,"
              "dm_change,static_dm_per_cell,steady_dm_per_cell,steady_spread,"
              "smallest_gap,final_gap,deformation_index,wall_seconds")
  {}

  FlowingLayoutsExperiment::~FlowingLayoutsExperiment() = default;

  void
  FlowingLayoutsExperiment::setup()
  {
    const double cell_volume =
      EvansFungShape::of(parameters.cells).exact_volume();
    std::vector<std::vector<CellPlacement>> placed;
    for (const auto &samples :
         parameters.layout_study.layouts(parameters.layout))
      for (const LayoutParameters &layout : samples)
        {
          const CellLayout cells =
            study_layout(layout, parameters.geometry, parameters.cells);
          same_cells_as.push_back(first_alike(placed, cells.placements()));
          placed.push_back(cells.placements());
          layouts.push_back(layout);
          hematocrits.push_back(cells.hematocrit(
            std::vector<double>(cells.placements().size(), cell_volume)));
          runs.push_back(derive_run(layout));
        }
    const TimeParameters &time = parameters.time;
    pcout << "  " << runs.size() << " flowing runs of "
          << time.n_steps * time.time_step << " s (" << time.n_steps
          << " steps), DM every " << parameters.immersed.diffusion_interval
          << " steps, in " << parameters.output_directory
          << "/<kind>_<n>_<seed>" << std::endl;
  }

  std::unique_ptr<RunParameters>
  FlowingLayoutsExperiment::derive_run(const LayoutParameters &layout) const
  {
    const std::string directory =
      parameters.output_directory + "/" + run_name(layout);
    std::vector<ParameterChange> changes{
      {"", "Experiment", "flow"},
      {"", "Output directory", directory},
      {"Layout", "Kind", name_of(layout.kind, layout_kind_names())},
      {"Layout", "Number of cells", std::to_string(layout.n_cells)},
      {"Layout", "Seed", std::to_string(layout.seed)},
      {"Immersed cells", "Enabled", "true"}};
    for (const ParameterChange &change :
         resumable_run(parameters, directory, parameters.time.n_steps))
      changes.push_back(change);
    auto run = std::make_unique<RunParameters>();
    run->derive(parameter_file_text, changes);
    return run;
  }

  FlowingLayoutResult
  FlowingLayoutsExperiment::run_one(const unsigned int r)
  {
    const Parameters &p = runs[r]->model();
    Timer             clock;
    UptakeHistory     uptake;
    run_derived_flow(
      *runs[r], FlowDomain::capillary(p), uptake, communicator, pcout, options);

    FlowingLayoutResult result;
    result.solves       = uptake.solves;
    result.static_dm    = result.solves.front().dm_total;
    result.final_gap    = result.solves.back().smallest_gap;
    result.smallest_gap = std::numeric_limits<double>::infinity();
    const double from   = result.solves.back().time - own.steady_window;
    double low = std::numeric_limits<double>::infinity(), high = -low, sum = 0.;
    unsigned int n_steady = 0;
    for (const auto &solve : result.solves)
      {
        result.smallest_gap = std::min(result.smallest_gap, solve.smallest_gap);
        if (solve.time < from - 1e-12 * own.steady_window)
          continue;
        low  = std::min(low, solve.dm_total);
        high = std::max(high, solve.dm_total);
        sum += solve.dm_total;
        ++n_steady;
      }
    result.steady_dm     = sum / n_steady;
    result.steady_spread = (high - low) / result.steady_dm;
    result.deformation   = uptake.mean_deformation;
    result.wall_seconds  = clock.wall_time();
    return result;
  }

  void
  FlowingLayoutsExperiment::add_rows(const unsigned int         r,
                                     const FlowingLayoutResult &result)
  {
    const LayoutParameters &layout = layouts[r];
    const std::string       kind   = name_of(layout.kind, layout_kind_names());
    const unsigned int      n      = layout.n_cells;
    for (const auto &solve : result.solves)
      history.add(kind,
                  n,
                  layout.seed,
                  hematocrits[r],
                  solve.time,
                  solve.dm_total,
                  solve.dm_total / n,
                  gap_text(solve.smallest_gap));
    summary.add(kind,
                n,
                layout.seed,
                hematocrits[r],
                result.static_dm,
                result.steady_dm,
                result.steady_dm / result.static_dm - 1.,
                result.static_dm / n,
                result.steady_dm / n,
                result.steady_spread,
                gap_text(result.smallest_gap),
                gap_text(result.final_gap),
                result.deformation,
                result.wall_seconds);
  }

  void
  FlowingLayoutsExperiment::execute()
  {
    Timer                            clock;
    std::vector<FlowingLayoutResult> results;
    for (unsigned int r = 0; r < runs.size(); ++r)
      {
        const LayoutParameters &layout = layouts[r];
        const std::string       name   = run_name(layout);
        pcout << "\nrun " << r + 1 << " of " << runs.size() << ": "
              << name_of(layout.kind, layout_kind_names()) << ", "
              << layout.n_cells << " cells, seed " << layout.seed
              << ", hematocrit " << hematocrits[r];
        write_on_rank_0(communicator, [&]() {
          const CellLayout cells(layout, parameters.geometry, parameters.cells);
          cells.table().write(parameters.output_directory + "/" +
                              cells.file_name());
        });
        if (same_cells_as[r] < r)
          {
            pcout << ": the cells of run " << same_cells_as[r] + 1
                  << ", whose results it takes" << std::endl;
            results.push_back(results[same_cells_as[r]]);
          }
        else
          {
            pcout << ", in " << runs[r]->model().output_directory << std::endl;
            TimerOutput::Scope scope(timer, name);
            results.push_back(run_one(r));
          }
        add_rows(r, results.back());
        write_on_rank_0(communicator, [&]() {
          history.write(parameters.output_directory + "/flowing_layouts.csv");
          summary.write(parameters.output_directory +
                        "/flowing_layouts_summary.csv");
        });
        const FlowingLayoutResult &result  = results.back();
        const double               elapsed = clock.wall_time();
        pcout << "run " << r + 1 << " of " << runs.size() << ": DM "
              << result.static_dm << " at rest, " << result.steady_dm
              << " steady (" << std::showpos
              << 100. * (result.steady_dm / result.static_dm - 1.)
              << std::noshowpos << " %, spread " << 100. * result.steady_spread
              << " % over the last " << own.steady_window
              << " s) µm³/(s Torr)  "
              << time_left_text(elapsed, r + 1, runs.size() - r - 1)
              << std::endl;
      }
  }
} // namespace rbc_ifem

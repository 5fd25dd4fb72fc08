#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/output.h>
#include <rbc_ifem/coupling/cell_boxes.h>
#include <rbc_ifem/coupling/contact_forces.h>
#include <rbc_ifem/ifem/run_report.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace rbc_ifem
{
  RunReport::RunReport(const Parameters &parameters,
                       const FlowDomain &domain,
                       const MPI_Comm    communicator)
    : parameters(parameters)
    , domain(domain)
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
  {}

  void
  RunReport::startup(const CellPopulation        &cells,
                     const CouplingTimeStepLimit &stable,
                     const double                 mesh_size,
                     const double                 time_step) const
  {
    const FluidParameters    &f           = parameters.fluid;
    const MembraneParameters &m           = parameters.membrane;
    const double              speed       = domain.velocity_scale;
    const double              length      = domain.length_scale;
    const double              spacing     = cells.point_spacing();
    const double              stable_step = stable.limit;

    pcout << "  cells: " << cells.size() << ", " << cells.n_points()
          << " membrane points, spacing up to " << spacing
          << " µm; fluid mesh size at the cells h = " << mesh_size << " µm\n"
          << "  Reynolds number ρ U L / μ = "
          << f.density * speed * length / f.viscosity
          << ", capillary number μ U / G = "
          << f.viscosity * speed / m.shear_modulus
          << " (U = " << domain.velocity_symbol
          << ", L = " << domain.length_symbol << ")\n"
          << "  explicit-coupling time step limit ≈ " << stable_step
          << " s (in-plane " << stable.in_plane << " s, bending "
          << stable.bending << " s"
          << (std::isfinite(stable.contact) ?
                ", repulsion at the starting gaps " + to_text(stable.contact) +
                  " s" :
                std::string())
          << "); explicit runs stay stable below about 0.7 of it "
             "(doc/ifem.md); advective limit "
          << stable.advective
          << " s (a point at U moves half the Maximum step displacement); "
             "coupling "
          << name_of(parameters.immersed.coupling, coupling_scheme_names())
          << ", Δt = " << time_step << " s ("
          << (parameters.time.automatic_time_step() ? "Time step = auto, " : "")
          << time_step / stable_step << " of the estimate)" << std::endl;
    warn(cells, stable, mesh_size, time_step);
  }

  void
  RunReport::warn(const CellPopulation        &cells,
                  const CouplingTimeStepLimit &stable,
                  const double                 mesh_size,
                  const double                 time_step) const
  {
    const double spacing     = cells.point_spacing();
    const double stable_step = stable.limit;
    // Measured (doc/ifem.md): 0.71 of the estimate stable over the default
    // run, 0.83 diverged after 112 steps.
    if (parameters.immersed.coupling == CouplingScheme::explicit_forces &&
        time_step > 0.75 * stable_step)
      pcout << "  WARNING: Time/Time step = " << time_step << " s is "
            << time_step / stable_step << " of the explicit-coupling estimate "
            << stable_step
            << " s; runs stay stable below about 0.7 of it: set it to at "
               "most "
            << 0.7 * stable_step
            << " s, or to auto, or set Immersed cells/Coupling = "
               "semi-implicit."
            << std::endl;
    if (time_step > 2. * stable.advective)
      pcout << "  WARNING: Time/Time step = " << time_step
            << " s is more than twice the advective limit " << stable.advective
            << " s: points moving at the run's speed may cross more than "
               "Immersed cells/Maximum step displacement of h in a step, "
               "which stops the run. Set it to auto, or below "
            << 2. * stable.advective << " s." << std::endl;
    const InteractionParameters &contact = parameters.interactions;
    if (cells.size() > 1 && contact.repulsion_pressure > 0. &&
        contact.repulsion_range < spacing)
      pcout << "  WARNING: Cell interactions/Repulsion range = "
            << contact.repulsion_range
            << " µm is shorter than the membrane point spacing " << spacing
            << " µm: where two membranes come closer than the spacing, a "
               "point of one may pass between the points of the other. Fine "
               "while the cells stay farther apart (cells.csv, min_gap): a "
               "membrane that crosses another stops the run, which says so. "
               "For cells pressed together, raise the range to at least "
            << spacing << " µm." << std::endl;
    if (spacing > 0.5 * mesh_size)
      pcout << "  WARNING: the membrane point spacing " << spacing
            << " µm exceeds half the fluid mesh size at the cells, h/2 = "
            << 0.5 * mesh_size
            << " µm (the paper's rule, against plasma leaking through the "
               "membrane). A leak shows as a change of a cell's volume, which "
               "the run watches (it stops above Immersed cells/Maximum volume "
               "change) and prints: fine if the volume change at the end "
               "stays well below 1%; if not, raise Cells/Surface refinements "
               "by one."
            << std::endl;
  }

  void
  RunReport::summary(const RunRecord      &record,
                     const CellPopulation &cells,
                     const unsigned int    n_run,
                     const double          wall_seconds) const
  {
    pcout << "  summary: t = " << record.time << " s, " << n_run << " steps in "
          << duration_text(wall_seconds) << ", "
          << wall_seconds / std::max(1u, n_run) << " s per step" << std::endl;
    summarize_dm(record);
    summarize_cells(cells);
  }

  void
  RunReport::load_balance(const CellPopulation &cells,
                          const unsigned int    points_here,
                          const unsigned int    fluid_cells_here) const
  {
    unsigned int owned = 0, kept = 0;
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        owned += cells.owners().owns(c);
        kept += cells.holds(c);
      }
    // The ghosts: the other cells within contact reach of the owned ones,
    // whose points the rank's contact search sees (MembraneInteraction).
    const std::vector<bool> near =
      CellBoxes(cells.membranes(), cells.positions(), domain.period)
        .near_owned(cells.owners(), contact_reach(parameters.interactions));
    const unsigned int ghosts =
      std::count(near.begin(), near.end(), true) - owned;
    const auto spread = [this](const unsigned int n) {
      const auto range = Utilities::MPI::min_max_avg(n, communicator);
      return std::to_string(static_cast<unsigned int>(range.min)) + "-" +
             std::to_string(static_cast<unsigned int>(range.max));
    };
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    pcout << "  per rank, least to most over " << n_ranks << ": "
          << (n_ranks > 1 && !cells.owners().shared() ?
                "a share of each of the " + std::to_string(cells.size()) +
                  " red cells it holds (fewer cells than ranks)" :
                "owns " + spread(owned) + " of the " +
                  std::to_string(cells.size()) +
                  " red cells (CellOwners), keeps the membranes of " +
                  spread(kept) + " (its own and the first) and sees " +
                  spread(ghosts) + " more in contact reach (ghosts)")
          << ", " << spread(points_here) << " membrane points in its "
          << spread(fluid_cells_here) << " fluid cells" << std::endl;
  }

  void
  RunReport::communication(const MpiTraffic  &during,
                           const unsigned int n_run,
                           const unsigned int handovers) const
  {
    const auto spread = [&](const unsigned long long count) {
      const auto range = Utilities::MPI::min_max_avg(
        static_cast<double>(count) / std::max(1u, n_run), communicator);
      std::ostringstream text;
      text << std::fixed << std::setprecision(0) << range.min << "-"
           << range.max;
      return text.str();
    };
    const std::string collectives      = spread(during.collectives);
    const std::string messages         = spread(during.messages);
    const std::string bytes            = spread(during.bytes);
    const std::string collective_bytes = spread(during.collective_bytes);
    pcout << "  per rank and step, least to most over "
          << Utilities::MPI::n_mpi_processes(communicator) << ": "
          << collectives << " collective MPI calls, " << messages
          << " messages sent, " << bytes << " bytes sent, " << collective_bytes
          << " bytes into collectives (MpiTraffic); " << handovers
          << " hand-overs of a red cell to another rank" << std::endl;
  }

  void
  RunReport::summarize_dm(const RunRecord &record) const
  {
    if (record.dm_history.empty())
      return;
    // 1 µm³/s = 6e-11 mL/min, and 1 mmHg = 1.000000142 Torr.
    const double to_ml_min_mmhg    = 60e-12 * 1.000000142;
    const auto [first_time, first] = record.dm_history.front();
    const auto [last_time, last]   = record.dm_history.back();
    if (record.dm_history.size() == 1)
      pcout << "  DM at t = " << first_time << " s " << first
            << " µm³/(s Torr), " << first * to_ml_min_mmhg << " mL/(min mmHg)"
            << std::endl;
    else
      pcout << "  DM at t = " << first_time << " s " << first
            << ", at t = " << last_time << " s " << last << " µm³/(s Torr) ("
            << std::showpos << 100. * (last / first - 1.) << std::noshowpos
            << "%); in mL/(min mmHg) " << first * to_ml_min_mmhg << " and "
            << last * to_ml_min_mmhg << std::endl;
  }

  void
  RunReport::summarize_cells(const CellPopulation &cells) const
  {
    const std::vector<CellShape> shapes = cells.shapes();
    double deformation = 0., volume_drift = 0., area_drift = 0.,
           local_area = 0.;
    for (unsigned int c = 0; c < shapes.size(); ++c)
      {
        local_area = std::max(local_area, shapes[c].largest_local_area_change);
        deformation += shapes[c].deformation_index / shapes.size();
        const double dv = shapes[c].volume / cells.reference_volume(c) - 1.;
        const double da = shapes[c].area / cells.reference_area(c) - 1.;
        volume_drift =
          std::abs(dv) > std::abs(volume_drift) ? dv : volume_drift;
        area_drift = std::abs(da) > std::abs(area_drift) ? da : area_drift;
      }
    pcout << "  cells at the end: deformation index " << deformation
          << (shapes.size() > 1 ? " (mean)" : "") << ", volume change "
          << 100. * volume_drift << "%, area change " << 100. * area_drift
          << "%" << (shapes.size() > 1 ? " (the largest over the cells)" : "")
          << ", largest local area change " << 100. * local_area
          << "% (the cell field area_change of cell_C.pvd)" << std::endl;
  }
} // namespace rbc_ifem

#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/ifem/parameters.h>

#include <deal.II/base/utilities.h>

#include <algorithm>

namespace rbc_ifem
{
  const SelectionNames<CouplingScheme> &
  coupling_scheme_names()
  {
    static const SelectionNames<CouplingScheme> names{
      {CouplingScheme::explicit_forces, "explicit"},
      {CouplingScheme::semi_implicit, "semi-implicit"}};
    return names;
  }

  const SelectionNames<MembraneFiles> &
  membrane_files_names()
  {
    static const SelectionNames<MembraneFiles> names{
      {MembraneFiles::per_cell, "per cell"},
      {MembraneFiles::grouped, "grouped"}};
    return names;
  }

  void
  TimeParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time");
    add_parameter(prm,
                  "Time step",
                  time_step_text,
                  "Time step Δt [s]: of the fluid's backward Euler step "
                  "and, with Immersed cells/Enabled, of the coupling: the "
                  "explicit one stays stable only below about 0.7 of the "
                  "estimate the run prints (doc/ifem.md), the "
                  "semi-implicit one far beyond it. auto: with immersed "
                  "cells half that estimate (explicit) or 10 times it "
                  "(semi-implicit), for the plasma alone 1e-3 s.",
                  PositiveOrAuto());
    prm.add_action("Time step", [this](const std::string &text) {
      time_step = Utilities::trim(text) == "auto" ? 0. : std::stod(text);
    });
    add_parameter(prm,
                  "Number of steps",
                  n_steps,
                  "How many time steps the run takes.",
                  Patterns::Integer(1));
    add_parameter(prm,
                  "Output interval",
                  output_interval,
                  "Write the fields (VTU) every this many steps and at the "
                  "last; the CSV tables are rewritten then too. Experiment "
                  "flow without cells has a flow.csv row for every step; "
                  "with Immersed cells/Enabled, flow.csv has a row for every "
                  "progress line (Immersed cells/Progress interval, and "
                  "every diffusion, output and checkpoint step) and "
                  "cells.csv one per cell at every output (doc/outputs.md).",
                  Patterns::Integer(1));
    prm.leave_subsection();
  }

  bool
  TimeParameters::automatic_time_step() const
  {
    return time_step == 0.;
  }

  double
  TimeParameters::plasma_time_step() const
  {
    return automatic_time_step() ? 1e-3 : time_step;
  }

  double
  TimeParameters::coupled_time_step(const CouplingTimeStepLimit &stable,
                                    const CouplingScheme         scheme) const
  {
    if (!automatic_time_step())
      return time_step;
    return std::min(stable.advective,
                    scheme == CouplingScheme::explicit_forces ?
                      0.5 * stable.limit :
                      semi_implicit_step_factor * stable.limit);
  }

  void
  ImmersedParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Immersed cells");
    add_coupling_parameters(prm);
    add_schedule_parameters(prm);
    add_force_parameters(prm);
    prm.leave_subsection();
  }

  void
  ImmersedParameters::add_coupling_parameters(ParameterHandler &prm)
  {
    add_parameter(prm,
                  "Enabled",
                  enabled,
                  "Experiment flow: true carries the red cells of "
                  "subsection Layout in the plasma (the immersed finite "
                  "element method: membrane forces spread to the fluid, "
                  "membranes moved with the interpolated velocity); false "
                  "solves for the plasma alone.");
    add_parameter(prm,
                  "Follow cells",
                  follow_cells,
                  "Move the computational frame with the cells: after "
                  "every step the frame velocity (Fluid/Frame velocity is "
                  "its start value) becomes the cells' mean velocity along "
                  "x, so a cell stays in the short segment. false keeps "
                  "Fluid/Frame velocity.");
    add_selection(
      prm,
      "Coupling",
      coupling,
      coupling_scheme_names(),
      "How the membrane forces enter the fluid step. "
      "semi-implicit (the default, the faster): the forces at "
      "its end, linearised with the membranes' "
      "exact tangent stiffness K, so the fluid operator gains "
      "Δt Sᵀ K S (S interpolates at the membrane points) and "
      "stays stable at many times the explicit scheme's limit; each FGMRES "
      "iteration then also interpolates, applies K and spreads. "
      "explicit (the paper's, kept for comparison): the forces "
      "at the step's start, so Δt must stay below the stability "
      "limit the run prints, which falls with the membrane "
      "stiffness (doc/ifem.md).");
  }

  void
  ImmersedParameters::add_schedule_parameters(ParameterHandler &prm)
  {
    add_parameter(prm,
                  "Diffusion interval",
                  diffusion_interval,
                  "Solve the CO diffusion on the current membrane shapes "
                  "at the start and every this many steps (a row of "
                  "dm.csv, the P field and the flux map); 0: never.",
                  Patterns::Integer(0));
    add_parameter(prm,
                  "Checkpoint interval",
                  checkpoint_interval,
                  "Write Output directory/checkpoint.bin every this many "
                  "steps (and at the last step); 0: never.",
                  Patterns::Integer(0));
    add_parameter(prm,
                  "Resume",
                  resume,
                  "Continue from Output directory/checkpoint.bin, written "
                  "by an earlier run of the same file (on any number of "
                  "MPI ranks), up to Time/Number of steps.");
    add_parameter(prm,
                  "Progress interval",
                  progress_interval,
                  "Print a progress line (step, time, solver iterations, "
                  "frame velocity, volume change and deformation index of "
                  "cell 0) every this many steps, and at every diffusion "
                  "solve (with DM) and output.",
                  Patterns::Integer(1));
    add_selection(
      prm,
      "Membrane files",
      membrane_files,
      membrane_files_names(),
      "How the membranes are written at every output (doc/outputs.md). "
      "per cell (the default, which the scripts of doc/scripts read): "
      "cell_C_SSSS.vtu and the series cell_C.pvd for every cell C, each "
      "by the rank that owns the cell. grouped: one series membranes.pvd "
      "of all cells, each output one membranes_SSSS.pvtu whose pieces are "
      "written by the ranks that own cells, each piece those cells with "
      "the field cell (the index): a few files per output however many "
      "the cells, and one series to open in ParaView; choose it for tens "
      "of cells or more.");
  }

  void
  ImmersedParameters::add_force_parameters(ParameterHandler &prm)
  {
    add_parameter(prm,
                  "Maximum step displacement",
                  max_step_displacement,
                  "The run stops, as diverged, if a membrane point moves "
                  "farther than this fraction of the fluid mesh size in "
                  "one step (the coupling is then unstable, or the step "
                  "too long to be accurate: reduce Time/Time step).",
                  GreaterThan());
    add_parameter(prm,
                  "Maximum volume change",
                  max_volume_change,
                  "The run stops, as diverged, if a cell's volume differs "
                  "from its reference volume by more than this fraction "
                  "(the volume penalty holds a stable run's within about "
                  "1%), and so it does if a cell's volume oscillates from "
                  "step to step with a growing amplitude (6 steps in a "
                  "row, each change above 1e-4): an unstable coupling.",
                  GreaterThan());
    add_parameter(prm,
                  "Tether stiffness",
                  tether_stiffness,
                  "0: the cells are free. > 0: every membrane point is "
                  "held at its starting position by a spring of this "
                  "stiffness [pN/µm], so the cells stay put and flow.csv's "
                  "held_force_x/y/z is the total force that holds them, "
                  "the drag's opposite (the held sphere of "
                  "doc/validation.md). Needs Follow cells = false.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Squeeze into lumen",
                  squeeze_into_lumen,
                  "true lets the cells be wider than the capillary (Cells/"
                  "Diameter up to and beyond twice Geometry/Capillary "
                  "radius): before the run, the wall closes in on each cell "
                  "in stages, the membrane relaxed to its static "
                  "equilibrium against it at each, so the cell starts "
                  "squeezed into the lumen with its stress-free reference "
                  "shape unchanged, and the wall repulsion keeps it there "
                  "while it flows. Needs Cell interactions/Wall pressure "
                  "> 0.");
    add_parameter(prm,
                  "Pushing forces",
                  pushing_forces,
                  "A constant force on each cell [pN], 'Fx, Fy, Fz' per "
                  "cell separated by ';', in the order of subsection "
                  "Layout (empty: none), spread over the membrane by area: "
                  "to drive one cell into another or against the wall "
                  "(prm/cells_in_contact.prm). Its total is part of "
                  "flow.csv's held_force.",
                  Patterns::List(Patterns::List(Patterns::Double(), 3, 3, ","),
                                 0,
                                 Patterns::List::max_int_value,
                                 ";"));
  }

  std::vector<Tensor<1, 3>>
  ImmersedParameters::pushing_force_vectors() const
  {
    std::vector<Tensor<1, 3>> forces;
    for (const std::string &force :
         Utilities::split_string_list(pushing_forces, ';'))
      {
        const std::vector<double> components =
          Utilities::string_to_double(Utilities::split_string_list(force, ','));
        forces.emplace_back();
        for (unsigned int d = 0; d < 3; ++d)
          forces.back()[d] = components[d];
      }
    return forces;
  }

  void
  ImmersedParameters::validate() const
  {
    if (tether_stiffness > 0. && follow_cells)
      throw InputError("Immersed cells/Follow cells",
                       "true",
                       "held cells (Immersed cells/Tether stiffness = " +
                         to_text(tether_stiffness) +
                         " pN/µm) need a frame at rest: set Follow cells = "
                         "false.");
  }
} // namespace rbc_ifem

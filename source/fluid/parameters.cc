#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_tools.h>
#include <rbc_ifem/fluid/parameters.h>

namespace rbc_ifem
{
  const SelectionNames<FluidModel> &
  fluid_model_names()
  {
    static const SelectionNames<FluidModel> names{
      {FluidModel::stokes, "Stokes"},
      {FluidModel::navier_stokes, "Navier-Stokes"}};
    return names;
  }

  void
  FluidParameters::add_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Fluid");
    add_selection(prm,
                  "Model",
                  model,
                  fluid_model_names(),
                  "Stokes: unsteady Stokes, the fast path (the capillary "
                  "Reynolds number ρ ū 2R / μ is about 4e-3 at the default 500 "
                  "µm/s in the 10 µm capillary; the run prints it); "
                  "Navier-Stokes: with the "
                  "convective term, Newton-Raphson in every time step.");
    add_parameter(prm,
                  "Viscosity",
                  viscosity,
                  "Dynamic viscosity μ of plasma (and of the cytoplasm: "
                  "viscosity ratio 1) [pN s/µm²]; 1.2e-3 is 1.2 mPa s.",
                  GreaterThan());
    add_parameter(prm,
                  "Density",
                  density,
                  "Density ρ [mg/µm³]; 1e-9 is 1000 kg/m³.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Inlet mean speed",
                  inlet_mean_speed,
                  "Mean speed ū of the Poiseuille inflow at x = 0, "
                  "u(r) = 2ū(1 - r²/R²) [µm/s]; capillary red cells move "
                  "at 300-700 µm/s.",
                  Patterns::Double());
    add_parameter(prm,
                  "Frame velocity",
                  frame_velocity,
                  "Velocity U_frame of the computational frame along x "
                  "[µm/s]: walls and inflow move at -U_frame in it. 0 is "
                  "the laboratory frame.",
                  Patterns::Double());
    add_parameter(prm,
                  "Linear solver tolerance",
                  linear_tolerance,
                  "FGMRES stops when the residual is this fraction of the "
                  "largest residual of the run (the problem's scale); "
                  "1e-6 leaves the solution 1e-6 from exact, far below "
                  "the discretisation error. (Diffusion/Linear solver "
                  "tolerance is a reduction factor of one solve's own "
                  "first residual instead.)",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Max linear iterations",
                  max_linear_iterations,
                  "FGMRES gives up (and the run stops) after this many "
                  "iterations.",
                  Patterns::Integer(1));
    add_parameter(prm,
                  "Newton tolerance",
                  newton_tolerance,
                  "Navier-Stokes: Newton stops when the residual has "
                  "fallen by this factor from its first value in the "
                  "step.",
                  Patterns::Double(0.));
    add_parameter(prm,
                  "Max Newton iterations",
                  max_newton_iterations,
                  "Navier-Stokes: the run stops if Newton has not "
                  "converged after this many iterations.",
                  Patterns::Integer(1));
    prm.leave_subsection();
  }
} // namespace rbc_ifem

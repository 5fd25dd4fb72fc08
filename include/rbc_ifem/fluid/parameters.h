#ifndef rbc_ifem_fluid_parameters_h
#define rbc_ifem_fluid_parameters_h

#include <rbc_ifem/base/parameter_tools.h>

#include <deal.II/base/parameter_handler.h>

namespace rbc_ifem
{
  using namespace dealii;

  /// How the plasma's momentum equation is solved (Fluid/Model).
  enum class FluidModel
  {
    stokes,       ///< unsteady Stokes: a constant operator, built once
    navier_stokes ///< with convection: Newton-Raphson in every step
  };

  const SelectionNames<FluidModel> &
  fluid_model_names();

  /**
   * The plasma and how its flow is solved (subsection "Fluid"). The
   * initializers are the defaults (see GeometryParameters). Units: µm, s, pN.
   */
  struct FluidParameters
  {
    FluidModel   model                 = FluidModel::stokes;
    double       viscosity             = 1.2e-3; ///< μ [pN s/µm²]
    double       density               = 1e-9;   ///< ρ [mg/µm³]
    double       inlet_mean_speed      = 500.;   ///< ū [µm/s]
    double       frame_velocity        = 0.;     ///< U_frame along x [µm/s]
    double       linear_tolerance      = 1e-6;   ///< relative, FGMRES
    unsigned int max_linear_iterations = 500;
    double       newton_tolerance = 1e-8; ///< relative to the first residual
    unsigned int max_newton_iterations = 20;

    void
    add_parameters(ParameterHandler &prm);
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_fluid_flow_drive_h
#define rbc_ifem_fluid_flow_drive_h

#include <rbc_ifem/fluid/parameters.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/base/function.h>
#include <deal.II/base/types.h>

#include <map>
#include <memory>
#include <optional>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Hagen-Poiseuille flow in the capillary, seen from a frame moving with
   * U_frame along x: v = (2ū(1 - r²/R²) - U_frame, 0, 0), p = 8μū(L - x)/R²
   * (zero at the outlet). Components: v_x, v_y, v_z, p. It is the inflow
   * profile of FluidProblem and the exact solution of its tests.
   */
  class PoiseuilleFlow : public Function<3>
  {
  public:
    PoiseuilleFlow(const double              mean_speed,
                   const double              frame_velocity,
                   const double              viscosity,
                   const GeometryParameters &geometry);

    double
    value(const Point<3> &p, const unsigned int component = 0) const override;

  private:
    const double mean_speed, frame_velocity, viscosity, radius, length;
  };

  /**
   * Simple shear v = (γ̇ y, 0, 0), p = 0: the flow that drives the box of
   * Experiment = shear (create_shear_box_mesh()). Components v_x, v_y, v_z, p.
   */
  class SimpleShearFlow : public Function<3>
  {
  public:
    explicit SimpleShearFlow(const double shear_rate);

    double
    value(const Point<3> &p, const unsigned int component = 0) const override;

  private:
    const double shear_rate;
  };

  /**
   * What drives a FluidProblem: the velocity prescribed on each Dirichlet
   * boundary, in the lab frame (a frame moving with U_frame sees it minus
   * U_frame e_x). Every other boundary is open, do-nothing.
   */
  struct FlowDrive
  {
    std::map<types::boundary_id, std::shared_ptr<const Function<3>>> dirichlet;
    /**
     * With a period L: the inlet and outlet faces are one, the flow (v and
     * p) periodic along x with this length, and there is no open boundary.
     */
    std::optional<double> period;
    /// A constant force density G e_x [pN/µm³]: the mean pressure gradient
    /// -dp/dx that drives a periodic segment.
    double pressure_gradient = 0.;

    /// The capillary of @p geometry: no slip on the wall, Poiseuille of mean
    /// speed ū at the inlet; with Geometry/Periodic, periodic_capillary().
    static FlowDrive
    capillary(const FluidParameters &fluid, const GeometryParameters &geometry);
    /**
     * The periodic capillary (Geometry/Periodic): no slip on the wall, and
     * the pressure gradient G = 8μū/R² that carries the Poiseuille flow of
     * mean speed ū through the empty segment.
     */
    static FlowDrive
    periodic_capillary(const FluidParameters    &fluid,
                       const GeometryParameters &geometry);
    /// The shear box: simple shear of rate γ̇ [1/s] on the walls y, z = const.
    static FlowDrive
    shear(const double shear_rate);
  };
} // namespace rbc_ifem

#endif

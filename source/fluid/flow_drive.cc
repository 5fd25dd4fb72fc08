#include <rbc_ifem/fluid/flow_drive.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

namespace rbc_ifem
{
  PoiseuilleFlow::PoiseuilleFlow(const double              mean_speed,
                                 const double              frame_velocity,
                                 const double              viscosity,
                                 const GeometryParameters &geometry)
    : Function<3>(4)
    , mean_speed(mean_speed)
    , frame_velocity(frame_velocity)
    , viscosity(viscosity)
    , radius(geometry.capillary_radius)
    , length(geometry.capillary_length)
  {}

  double
  PoiseuilleFlow::value(const Point<3> &p, const unsigned int component) const
  {
    const double r2 = (p[1] * p[1] + p[2] * p[2]) / (radius * radius);
    switch (component)
      {
        case 0:
          return 2. * mean_speed * (1. - r2) - frame_velocity;
        case 3:
          return 8. * viscosity * mean_speed * (length - p[0]) /
                 (radius * radius);
        default:
          return 0.;
      }
  }


  SimpleShearFlow::SimpleShearFlow(const double shear_rate)
    : Function<3>(4)
    , shear_rate(shear_rate)
  {}

  double
  SimpleShearFlow::value(const Point<3> &p, const unsigned int component) const
  {
    return component == 0 ? shear_rate * p[1] : 0.;
  }


  FlowDrive
  FlowDrive::capillary(const FluidParameters    &fluid,
                       const GeometryParameters &geometry)
  {
    if (geometry.periodic)
      return periodic_capillary(fluid, geometry);
    FlowDrive drive;
    drive.dirichlet[FluidBoundary::wall] =
      std::make_shared<Functions::ZeroFunction<3>>(4);
    drive.dirichlet[FluidBoundary::inlet] = std::make_shared<PoiseuilleFlow>(
      fluid.inlet_mean_speed, 0., fluid.viscosity, geometry);
    return drive;
  }

  FlowDrive
  FlowDrive::periodic_capillary(const FluidParameters    &fluid,
                                const GeometryParameters &geometry)
  {
    FlowDrive drive;
    drive.dirichlet[FluidBoundary::wall] =
      std::make_shared<Functions::ZeroFunction<3>>(4);
    drive.period        = geometry.capillary_length;
    const double radius = geometry.capillary_radius;
    drive.pressure_gradient =
      8. * fluid.viscosity * fluid.inlet_mean_speed / (radius * radius);
    return drive;
  }

  FlowDrive
  FlowDrive::shear(const double shear_rate)
  {
    FlowDrive drive;
    drive.dirichlet[FluidBoundary::wall] =
      std::make_shared<SimpleShearFlow>(shear_rate);
    return drive;
  }
} // namespace rbc_ifem

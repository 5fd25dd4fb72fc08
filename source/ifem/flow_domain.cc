#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/ifem/flow_domain.h>

#include <deal.II/grid/grid_generator.h>

#include <cmath>

namespace rbc_ifem
{
  void
  create_shear_box_mesh(Triangulation<3>   &triangulation,
                        const Tensor<1, 3> &box,
                        const double        cell_size,
                        const unsigned int  n_global_refinements)
  {
    std::vector<unsigned int> repetitions(3);
    for (unsigned int d = 0; d < 3; ++d)
      repetitions[d] =
        static_cast<unsigned int>(std::lround(box[d] / cell_size));
    const Point<3> corner(box / 2.);
    GridGenerator::subdivided_hyper_rectangle(
      triangulation, repetitions, -corner, corner, true);
    // colorize numbers the faces 2d (low) and 2d + 1 (high) along axis d.
    for (const auto &face : triangulation.active_face_iterators())
      if (face->at_boundary())
        {
          const types::boundary_id colour = face->boundary_id();
          face->set_boundary_id(colour == 0 ? FluidBoundary::inlet :
                                colour == 1 ? FluidBoundary::outlet :
                                              FluidBoundary::wall);
        }
    triangulation.refine_global(n_global_refinements);
  }

  FlowDomain
  FlowDomain::capillary(const Parameters &parameters)
  {
    FlowDomain domain;
    domain.kind  = Kind::capillary;
    domain.drive = FlowDrive::capillary(parameters.fluid, parameters.geometry);
    domain.placements =
      CellLayout(parameters.layout, parameters.geometry, parameters.cells)
        .placements();
    return domain;
  }

  FlowDomain
  FlowDomain::shear_box(const Parameters &parameters)
  {
    FlowDomain domain;
    domain.kind       = Kind::shear_box;
    domain.shear_rate = parameters.shear.shear_rate;
    domain.drive      = FlowDrive::shear(domain.shear_rate);
    domain.placements = {CellPlacement{Point<3>(), parameters.cells.axis}};
    return domain;
  }

  void
  FlowDomain::create_mesh(Triangulation<3> &triangulation,
                          const Parameters &parameters) const
  {
    if (kind == Kind::capillary)
      create_fluid_mesh(triangulation,
                        parameters.geometry,
                        parameters.mesh.fluid_global_refinements);
    else
      create_shear_box_mesh(triangulation,
                            parameters.shear.box,
                            parameters.cells.diameter,
                            parameters.mesh.fluid_global_refinements);
  }

  double
  FlowDomain::velocity_scale(const Parameters &parameters) const
  {
    return kind == Kind::capillary ?
             std::abs(parameters.fluid.inlet_mean_speed) :
             shear_rate * parameters.cells.diameter / 2.;
  }

  double
  FlowDomain::length_scale(const Parameters &parameters) const
  {
    return kind == Kind::capillary ? 2. * parameters.geometry.capillary_radius :
                                     parameters.cells.diameter / 2.;
  }

  std::string
  FlowDomain::name() const
  {
    return kind == Kind::capillary ? "the capillary" : "the shear box";
  }
} // namespace rbc_ifem

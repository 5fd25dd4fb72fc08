#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/shear_box_mesh.h>
#include <rbc_ifem/ifem/flow_domain.h>

#include <cmath>

namespace rbc_ifem
{
  FlowDomain
  FlowDomain::capillary(const Parameters &parameters)
  {
    FlowDomain domain;
    domain.name   = "the capillary";
    domain.drive  = FlowDrive::capillary(parameters.fluid, parameters.geometry);
    domain.period = parameters.geometry.period();
    // Cells squeezed into the lumen are placed along the axis as if it were
    // wide enough; IFEMSimulation then squeezes them.
    GeometryParameters layout_geometry = parameters.geometry;
    if (parameters.immersed.squeeze_into_lumen)
      layout_geometry.capillary_radius =
        std::max(layout_geometry.capillary_radius,
                 0.5 * parameters.cells.diameter + 1.);
    domain.placements =
      CellLayout(parameters.layout, layout_geometry, parameters.cells)
        .placements();
    domain.create_mesh =
      [geometry = parameters.geometry](Triangulation<3> &triangulation) {
        create_fluid_mesh(triangulation, geometry, 0);
      };
    Triangulation<3> coarse;
    domain.create_mesh(coarse);
    domain.n_coarse_cells       = coarse.n_active_cells();
    domain.n_global_refinements = parameters.mesh.fluid_global_refinements;
    domain.volume =
      numbers::PI *
      Utilities::fixed_power<2>(parameters.geometry.capillary_radius) *
      parameters.geometry.capillary_length;
    domain.wall_radius     = parameters.geometry.capillary_radius;
    domain.velocity_scale  = std::abs(parameters.fluid.inlet_mean_speed);
    domain.velocity_symbol = "ū";
    domain.length_scale    = 2. * parameters.geometry.capillary_radius;
    domain.length_symbol   = "2R";
    return domain;
  }

  FlowDomain
  FlowDomain::shear_box(const Tensor<1, 3> &box,
                        const double        shear_rate,
                        const Parameters   &parameters)
  {
    FlowDomain domain;
    domain.name        = "the shear box";
    domain.drive       = FlowDrive::shear(shear_rate);
    domain.placements  = {CellPlacement{Point<3>(), parameters.cells.axis}};
    domain.create_mesh = [box, cell_size = parameters.cells.diameter](
                           Triangulation<3> &triangulation) {
      create_shear_box_mesh(triangulation, box, cell_size, 0);
    };
    Triangulation<3> coarse;
    domain.create_mesh(coarse);
    domain.n_coarse_cells       = coarse.n_active_cells();
    domain.n_global_refinements = parameters.mesh.fluid_global_refinements;
    domain.volume               = box[0] * box[1] * box[2];
    domain.velocity_scale       = shear_rate * parameters.cells.diameter / 2.;
    domain.velocity_symbol      = "γ̇ a";
    domain.length_scale         = parameters.cells.diameter / 2.;
    domain.length_symbol        = "a";
    return domain;
  }
} // namespace rbc_ifem

#include <rbc_ifem/diffusion/cut_cell_diffusion.h>

#include <deal.II/fe/fe_q.h>

namespace rbc_ifem
{
  CutCellDiffusion::CutCellDiffusion(
    const CutCellGeometry                     &geometry,
    const DiffusionParameters                 &parameters,
    const std::function<double(unsigned int)> &permeability,
    const types::boundary_id                   pressure_boundary,
    TimerOutput                               &timer)
    : CutCellProblem(geometry,
                     parameters,
                     permeability,
                     pressure_boundary,
                     timer)
  {
    set_up_system(FE_Q<3>(parameters.degree));
  }

  double
  CutCellDiffusion::dm_total() const
  {
    return flow_per_pressure();
  }

  std::vector<unsigned int>
  CutCellDiffusion::fields_on(const Triangulation<3>::cell_iterator &cell) const
  {
    if (geometry.location(cell) != NonMatching::LocationToLevelSet::outside)
      return {0};
    return {};
  }

  NonMatching::RegionUpdateFlags
  CutCellDiffusion::assembly_flags() const
  {
    NonMatching::RegionUpdateFlags flags;
    flags.inside  = update_gradients | update_JxW_values;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    return flags;
  }

  void
  CutCellDiffusion::add_cell_terms(
    const NonMatching::FEValues<3>            &values,
    const DoFHandler<3>::active_cell_iterator &cell,
    const CutCellShapes                       &shapes,
    FullMatrix<double>                        &matrix) const
  {
    if (const auto &plasma = values.get_inside_fe_values())
      add_plasma_diffusion(*plasma,
                           permeability(cell->material_id()),
                           shapes,
                           matrix);
    if (const auto &membrane = values.get_surface_fe_values())
      add_membrane_coupling(*membrane, membrane_coupling(cell), shapes, matrix);
  }

  MembraneCoupling
  CutCellDiffusion::membrane_coupling(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    const double plasma = permeability(cell->material_id());
    return {plasma, 0., nitsche_weight(cell) * plasma};
  }
} // namespace rbc_ifem

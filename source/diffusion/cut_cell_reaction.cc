#include <rbc_ifem/diffusion/cut_cell_reaction.h>
#include <rbc_ifem/diffusion/side_field.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <cmath>
#include <stdexcept>

namespace rbc_ifem
{
  CutCellReaction::CutCellReaction(
    const CutCellGeometry                     &geometry,
    const DiffusionParameters                 &parameters,
    const std::function<double(unsigned int)> &permeability,
    const types::boundary_id                   pressure_boundary,
    const double                               cell_permeability,
    const double                               rate,
    TimerOutput                               &timer)
    : CutCellProblem(geometry,
                     parameters,
                     permeability,
                     pressure_boundary,
                     timer)
    , cell_permeability(cell_permeability)
    , rate(rate)
  {
    if (geometry.n_colours() == 0)
      throw std::logic_error("CutCellReaction needs a CutCellGeometry that "
                             "separates the cells' insides.");
    // With a reaction, P inside the cells is a field of its own (one per
    // colour): zero outside them, as the plasma's is inside.
    const auto side = [this](const bool plasma) {
      return [this, plasma](const DoFHandler<3>::cell_iterator &cell) {
        const std::vector<unsigned int> fields = fields_on(cell);
        const bool there = plasma ? fields.front() == 0 : fields.back() > 0;
        return there ? (plasma ? 0u : fields.back()) :
                       numbers::invalid_unsigned_int;
      };
    };
    plasma_pressure = std::make_unique<SideField>("co_pressure", side(true));
    cell_pressure =
      std::make_unique<SideField>("co_pressure_cell", side(false));
    set_up_system(
      FESystem<3>(FE_Q<3>(parameters.degree), 1 + geometry.n_colours()));
  }

  double
  CutCellReaction::dl_total() const
  {
    return flow_per_pressure();
  }

  std::vector<unsigned int>
  CutCellReaction::fields_on(const Triangulation<3>::cell_iterator &cell) const
  {
    return plasma_and_cell_fields(cell);
  }

  NonMatching::RegionUpdateFlags
  CutCellReaction::assembly_flags() const
  {
    NonMatching::RegionUpdateFlags flags;
    flags.inside  = update_gradients | update_JxW_values;
    flags.outside = update_values | update_gradients | update_JxW_values;
    flags.surface = update_values | update_gradients | update_JxW_values |
                    update_normal_vectors;
    return flags;
  }

  void
  CutCellReaction::add_cell_terms(
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
    if (const auto &cytoplasm = values.get_outside_fe_values())
      add_cytoplasm_reaction(
        *cytoplasm, cell_permeability, rate, shapes, matrix);
    if (const auto &membrane = values.get_surface_fe_values())
      add_membrane_coupling(*membrane, membrane_coupling(cell), shapes, matrix);
  }

  MembraneCoupling
  CutCellReaction::membrane_coupling(
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    const double gamma  = nitsche_weight(cell);
    const double plasma = permeability(cell->material_id());
    const double inside = cell_permeability;
    const double mh =
      std::sqrt(rate / inside) * cell->minimum_vertex_distance();
    const double stiff = inside * std::sqrt(1. + mh * mh);
    const double w0 = stiff / (plasma + stiff), w1 = 1. - w0;
    return {w0 * plasma,
            w1 * inside,
            2. * gamma * (w0 * w0 * plasma + w1 * w1 * inside)};
  }

  double
  CutCellReaction::field_permeability(
    const unsigned int                         field,
    const DoFHandler<3>::active_cell_iterator &cell) const
  {
    return field == 0 ? CutCellProblem::field_permeability(field, cell) :
                        cell_permeability;
  }

  void
  CutCellReaction::add_pressure_fields(DataOut<3> &data_out) const
  {
    data_out.add_data_vector(solution, *plasma_pressure);
    data_out.add_data_vector(solution, *cell_pressure);
  }
} // namespace rbc_ifem

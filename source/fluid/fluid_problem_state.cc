#include <rbc_ifem/fluid/fluid_problem.h>

#include <algorithm>

// The state of a FluidProblem that a checkpoint keeps, per mesh cell.

namespace rbc_ifem
{
  namespace
  {
    /// The cell of @p dof_handler that is @p cell of its triangulation.
    DoFHandler<3>::active_cell_iterator
    dof_cell(const Triangulation<3>::cell_iterator &cell,
             const DoFHandler<3>                   &dof_handler)
    {
      return {&dof_handler.get_triangulation(),
              cell->level(),
              cell->index(),
              &dof_handler};
    }
  } // namespace

  unsigned int
  FluidProblem::n_dofs_per_cell() const
  {
    return velocity_dofs.get_fe().n_dofs_per_cell() +
           pressure_dofs.get_fe().n_dofs_per_cell();
  }

  FluidState
  FluidProblem::state() const
  {
    FluidState state;
    state.frame_velocity = frame_velocity;
    state.residual_scale = residual_scale;
    state.has_earlier    = earlier.size() > 0;
    state.n_dofs         = n_dofs();
    return state;
  }

  CellRecords
  FluidProblem::cell_values() const
  {
    std::vector<const FluidVector *> fields{&current};
    FluidVector                      ghosted_earlier;
    if (earlier.size() > 0)
      {
        ghosted_earlier = earlier;
        ghosted_earlier.update_ghost_values();
        fields.push_back(&ghosted_earlier);
      }
    CellRecords         records(fields.size() * n_dofs_per_cell());
    std::vector<double> values;
    Vector<double>      v_values(velocity_dofs.get_fe().n_dofs_per_cell()),
      p_values(pressure_dofs.get_fe().n_dofs_per_cell());
    for (const auto &cell : velocity_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          values.clear();
          for (const FluidVector *field : fields)
            {
              cell->get_dof_values(field->block(0), v_values);
              dof_cell(cell, pressure_dofs)
                ->get_dof_values(field->block(1), p_values);
              values.insert(values.end(), v_values.begin(), v_values.end());
              values.insert(values.end(), p_values.begin(), p_values.end());
            }
          records.add(cell->id(), values);
        }
    return records;
  }

  void
  FluidProblem::set_cell_values(const CellRecords &records,
                                const unsigned int offset,
                                FluidVector       &v) const
  {
    const unsigned int n_v = velocity_dofs.get_fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> v_dofs(n_v),
      p_dofs(pressure_dofs.get_fe().n_dofs_per_cell());
    v.zero_out_ghost_values();
    for (unsigned int r = 0; r < records.size(); ++r)
      {
        const auto cell =
          velocity_dofs.get_triangulation().create_cell_iterator(
            records.cell(r));
        dof_cell(cell, velocity_dofs)->get_dof_indices(v_dofs);
        dof_cell(cell, pressure_dofs)->get_dof_indices(p_dofs);
        const ArrayView<const double> values = records.values(r);
        // A DoF of an owned cell that another rank owns is that rank's to
        // set: it has a cell of its own there.
        for (unsigned int i = 0; i < v_dofs.size(); ++i)
          if (v.block(0).in_local_range(v_dofs[i]))
            v.block(0)(v_dofs[i]) = values[offset + i];
        for (unsigned int i = 0; i < p_dofs.size(); ++i)
          if (v.block(1).in_local_range(p_dofs[i]))
            v.block(1)(p_dofs[i]) = values[offset + n_v + i];
      }
    v.update_ghost_values();
  }

  void
  FluidProblem::set_state(const FluidState &state, const CellRecords &owned)
  {
    AssertThrow(owned.size() == 0 ||
                  owned.values_per_cell() ==
                    (state.has_earlier ? 2 : 1) * n_dofs_per_cell(),
                ExcMessage("The fluid's cell values do not fit its DoFs."));
    set_cell_values(owned, 0, current);
    if (state.has_earlier)
      {
        earlier.reinit(current);
        set_cell_values(owned, n_dofs_per_cell(), earlier);
        earlier.zero_out_ghost_values();
      }
    frame_velocity = state.frame_velocity;
    residual_scale = state.residual_scale;
  }
} // namespace rbc_ifem

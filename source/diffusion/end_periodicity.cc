#include <rbc_ifem/diffusion/end_periodicity.h>
#include <rbc_ifem/geometry/capillary_mesh.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_tools.h>

namespace rbc_ifem
{
  namespace
  {
    using DoFCell = DoFHandler<3>::cell_iterator;

    /// Whether the active @p cell has P: seen here, and not inside a
    /// membrane (FE_Nothing).
    bool
    carries_pressure(const DoFCell &cell)
    {
      return !cell->is_artificial() && cell->get_fe().n_dofs_per_cell() > 0;
    }

    /// The DoFs of the active faces @p f_in of @p inlet and @p f_out of
    /// @p outlet, images of each other, constrained as
    /// make_end_periodicity_constraints() says.
    void
    constrain_face_pair(const DoFCell             &inlet,
                        const unsigned int         f_in,
                        const DoFCell             &outlet,
                        const unsigned int         f_out,
                        AffineConstraints<double> &constraints)
    {
      const unsigned int fe_index = inlet->active_fe_index();
      AssertThrow(outlet->active_fe_index() == fe_index,
                  ExcMessage("The two end faces of a periodic pair carry "
                             "different finite elements."));
      const unsigned int n = inlet->get_fe().n_dofs_per_face(f_in);
      std::vector<types::global_dof_index> in(n), out(n);
      inlet->face(f_in)->get_dof_indices(in, fe_index);
      outlet->face(f_out)->get_dof_indices(out, fe_index);
      for (unsigned int k = 0; k < n; ++k)
        if (!constraints.is_constrained(out[k]))
          {
            constraints.add_line(out[k]);
            constraints.add_entry(out[k], in[k], 1.);
          }
        else if (!constraints.is_constrained(in[k]) &&
                 constraints.get_constraint_entries(out[k])->empty())
          {
            constraints.add_line(in[k]);
            constraints.add_entry(in[k], out[k], 1.);
          }
    }

    /// The pairs of active faces below the end faces @p f_in of @p inlet
    /// and @p f_out of @p outlet, images of each other.
    void
    constrain_end_faces(const DoFCell             &inlet,
                        const unsigned int         f_in,
                        const DoFCell             &outlet,
                        const unsigned int         f_out,
                        AffineConstraints<double> &constraints)
    {
      if ((inlet->is_active() && inlet->is_artificial()) ||
          (outlet->is_active() && outlet->is_artificial()))
        return;
      AssertThrow(inlet->has_children() == outlet->has_children(),
                  ExcMessage("The end faces of the diffusion mesh are not "
                             "refined alike (match_end_refinement())."));
      if (inlet->is_active())
        {
          if (carries_pressure(inlet) && carries_pressure(outlet))
            constrain_face_pair(inlet, f_in, outlet, f_out, constraints);
          return;
        }
      for (unsigned int i = 0; i < GeometryInfo<3>::max_children_per_face; ++i)
        constrain_end_faces(
          inlet->child(GeometryInfo<3>::child_cell_on_face(
            RefinementCase<3>::isotropic_refinement, f_in, i)),
          f_in,
          outlet->child(GeometryInfo<3>::child_cell_on_face(
            RefinementCase<3>::isotropic_refinement, f_out, i)),
          f_out,
          constraints);
    }
  } // namespace

  void
  make_end_periodicity_constraints(const DoFHandler<3>       &dof_handler,
                                   AffineConstraints<double> &constraints)
  {
    std::vector<GridTools::PeriodicFacePair<DoFCell>> ends;
    GridTools::collect_periodic_faces(dof_handler,
                                      DiffusionBoundary::inlet_end,
                                      DiffusionBoundary::outlet_end,
                                      /*direction=*/0,
                                      ends);
    for (const auto &pair : ends)
      {
        // A translation along x: the subfaces of the two match in order.
        AssertThrow(pair.orientation == std::bitset<3>(1), ExcInternalError());
        constrain_end_faces(pair.cell[0],
                            pair.face_idx[0],
                            pair.cell[1],
                            pair.face_idx[1],
                            constraints);
      }
  }
} // namespace rbc_ifem

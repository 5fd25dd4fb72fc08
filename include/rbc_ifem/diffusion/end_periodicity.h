#ifndef rbc_ifem_diffusion_end_periodicity_h
#define rbc_ifem_diffusion_end_periodicity_h

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * P periodic between the end faces of a periodic segment's diffusion mesh
   * (boundary ids DiffusionBoundary::inlet_end and outlet_end), added to
   * @p constraints, which already hold the hanging nodes, the boundary
   * values and the DoFs held at zero. The ends must be refined alike
   * (match_end_refinement()); the DoFs of each active end face are then
   * paired with those of its image, in order (a translation along x).
   *
   * Each pair is constrained the same way on every rank, whatever the rank
   * sees of the hanging nodes: the outlet DoF to the inlet one, unless the
   * outlet DoF is already constrained; and if a value holds it (a boundary
   * value or zero), the inlet DoF to it, unless that is constrained too.
   * Hanging nodes tie DoFs of one end to DoFs of the same end, so no chain
   * of constraints leads from the inlet back to the outlet, and
   * AffineConstraints::make_consistent_in_parallel(), which keeps one
   * rank's line for each DoF, cannot join two ranks' lines into a cycle.
   * DoFTools::make_periodicity_constraints() decides each pair by what the
   * rank has seen so far, so two ranks can decide a pair two ways: the cycle
   * on which close() never returned (doc/diffusion.md).
   *
   * Faces of cells without DoFs (FE_Nothing inside a membrane that crosses
   * the end) and faces a rank does not see are left out.
   */
  void
  make_end_periodicity_constraints(const DoFHandler<3>       &dof_handler,
                                   AffineConstraints<double> &constraints);
} // namespace rbc_ifem

#endif

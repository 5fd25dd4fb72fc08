#ifndef rbc_ifem_diffusion_cut_cell_diffusion_h
#define rbc_ifem_diffusion_cut_cell_diffusion_h

#include <rbc_ifem/diffusion/cut_cell_problem.h>

namespace rbc_ifem
{
  /**
   * Steady CO uptake on cut cells, the membrane sink (Diffusion/Method =
   * cut cell): the plasma is the part of the diffusion mesh outside every
   * red cell, described by the level set of the CutCellGeometry, and P = 0
   * holds on its boundary, the membranes, by Nitsche's method, as in
   * deal.II's step-85:
   *
   *   find P in Q_k on the cells that reach into the plasma such that
   *   (αD ∇P, ∇q)_Ωh − (αD ∂ₙP, q)_Γh − (αD ∂ₙq, P)_Γh
   *     + (γ_N k(k+1) αD/h P, q)_Γh + g(P, q) = 0   for all q,
   *
   * with n the normal out of the plasma on the discrete membranes Γh and the
   * ghost penalty g(P, q) = Σ_F Σ_{j=1..k} γ_g αD h^(2j−1) ([∂ₙʲP], [∂ₙʲq])_F
   * on the faces F of cut cells, which bounds the condition number however
   * the membranes cut the cells. Its terms: add_plasma_diffusion(),
   * add_membrane_coupling() with P₁ = 0, add_ghost_penalty().
   *
   * P has no kink inside any cell (the cell interiors are not part of the
   * problem), so DM converges at the order of the geometry and the
   * symmetric, adjoint-consistent Nitsche flux: about k + 1. The flux into
   * each membrane and its map are CutCellProblem's.
   */
  class CutCellDiffusion : public CutCellProblem
  {
  public:
    /**
     * Set up the problem of @p parameters on @p geometry (which must
     * outlive it): αD = @p permeability(material id), P = P_A on boundary
     * @p pressure_boundary; DoFs, constraints and sparsity.
     */
    CutCellDiffusion(const CutCellGeometry                     &geometry,
                     const DiffusionParameters                 &parameters,
                     const std::function<double(unsigned int)> &permeability,
                     const types::boundary_id pressure_boundary,
                     TimerOutput             &timer);

    /// DM = total_flow() / P_A [µm³ s⁻¹ Torr⁻¹].
    double
    dm_total() const;

  protected:
    /// The plasma's field, on the cells that reach into the plasma.
    std::vector<unsigned int>
    fields_on(const Triangulation<3>::cell_iterator &cell) const override;

    NonMatching::RegionUpdateFlags
    assembly_flags() const override;

    void
    add_cell_terms(const NonMatching::FEValues<3>            &values,
                   const DoFHandler<3>::active_cell_iterator &cell,
                   const CutCellShapes                       &shapes,
                   FullMatrix<double> &matrix) const override;

    /// αD, 0 and γ_N k(k+1) αD/h.
    MembraneCoupling
    membrane_coupling(
      const DoFHandler<3>::active_cell_iterator &cell) const override;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_diffusion_cut_cell_reaction_h
#define rbc_ifem_diffusion_cut_cell_reaction_h

#include <rbc_ifem/diffusion/cut_cell_problem.h>

#include <deal.II/numerics/data_postprocessor.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * Finite CO uptake on cut cells (Diffusion/Uptake = reaction): instead of
   * P = 0 on the membranes, CO diffuses on through them into the cells,
   * whose cytoplasm has the permeability α_cD_c and binds it at the rate
   * k P per unit volume:
   *
   *   −∇·(αD ∇P) = 0 in the plasma,  −∇·(α_c D_c ∇P) + k P = 0 in the
   *   cells,  P and the flux continuous across the membranes.
   *
   * Each side has its own field (P₀ on the mesh cells that reach into the
   * plasma, P₁ on those that reach into a red cell, the DoFs of a field
   * outside its cells held at zero), glued by the symmetric Nitsche terms
   * of Hansbo & Hansbo (2002):
   *
   *   − ({αD ∂ₙP}, [q])_Γh − ([P], {αD ∂ₙq})_Γh + (β [P], [q])_Γh,
   *
   * [P] = P₀ − P₁, {αD ∂ₙP} = w₀ αD ∂ₙP₀ + w₁ α_cD_c ∂ₙP₁, and each
   * field has its ghost penalty. The weights w₀ = κ'/(αD + κ'),
   * w₁ = 1 − w₀ take the flux from the side that resolves it: Hansbo's
   * κ' = α_cD_c where the reaction is slow on the scale of the mesh, and
   * with κ' = α_cD_c √(1 + (m h)²), m² = k/(α_cD_c), the plasma's as
   * the reaction's boundary layer inside the membrane (thickness 1/m)
   * becomes thinner than the cells: as k → ∞ the problem becomes the
   * membrane sink's (P₁ → 0) and so does the discrete one.
   * β = 2 γ_N k(k+1) (w₀² αD + w₁² α_cD_c)/h. Its terms:
   * add_plasma_diffusion(), add_cytoplasm_reaction(),
   * add_membrane_coupling(), add_ghost_penalty() on every field.
   *
   * The flows are then the CO bound inside each cell (the flux
   * j = −{αD ∂ₙP} + β [P] into it, summed over its membrane; over all
   * membranes it equals ∫ k P₁), and their total per P_A is DL.
   *
   * P₁ of two red cells whose mesh cells touch must not share DoFs (a thin
   * plasma gap would join their insides, and their ghost penalties): the
   * geometry colours the red cells so that such neighbours differ, and
   * each colour has a field of its own, FESystem(FE_Q(k), 1 + colours).
   */
  class CutCellReaction : public CutCellProblem
  {
  public:
    /**
     * Set up the problem of @p parameters on @p geometry (which must
     * outlive it, built with CutCellGeometry::Options::separate_insides):
     * αD = @p permeability(material id) in the plasma and the wall,
     * @p cell_permeability (α_cD_c, µm²/(s Torr)) and the binding rate
     * @p rate (k, s⁻¹ Torr⁻¹) in the cells, P = P_A on boundary
     * @p pressure_boundary; DoFs, constraints and sparsity.
     */
    CutCellReaction(const CutCellGeometry                     &geometry,
                    const DiffusionParameters                 &parameters,
                    const std::function<double(unsigned int)> &permeability,
                    const types::boundary_id pressure_boundary,
                    const double             cell_permeability,
                    const double             rate,
                    TimerOutput             &timer);

    /// DL = total_flow() / P_A [µm³ s⁻¹ Torr⁻¹]: the CO bound inside the
    /// cells per Torr of alveolar pressure.
    double
    dl_total() const;

  protected:
    /// The plasma's field where the cell reaches into the plasma, and the
    /// field of the red cell it reaches into, if any.
    std::vector<unsigned int>
    fields_on(const Triangulation<3>::cell_iterator &cell) const override;

    NonMatching::RegionUpdateFlags
    assembly_flags() const override;

    void
    add_cell_terms(const NonMatching::FEValues<3>            &values,
                   const DoFHandler<3>::active_cell_iterator &cell,
                   const CutCellShapes                       &shapes,
                   FullMatrix<double> &matrix) const override;

    /// w₀ αD, w₁ α_cD_c and 2 γ_N k(k+1) (w₀² αD + w₁² α_cD_c)/h.
    MembraneCoupling
    membrane_coupling(
      const DoFHandler<3>::active_cell_iterator &cell) const override;

    /// The cytoplasm's α_cD_c for the fields inside the cells.
    double
    field_permeability(
      const unsigned int                         field,
      const DoFHandler<3>::active_cell_iterator &cell) const override;

    /// P in the plasma as "co_pressure", inside the cells as
    /// "co_pressure_cell", each zero on the other side.
    void
    add_pressure_fields(DataOut<3> &data_out) const override;

  private:
    const double cell_permeability;
    const double rate;
    /// The two sides' P for the output (DataOut keeps references to them).
    std::unique_ptr<const DataPostprocessor<3>> plasma_pressure, cell_pressure;
  };
} // namespace rbc_ifem

#endif

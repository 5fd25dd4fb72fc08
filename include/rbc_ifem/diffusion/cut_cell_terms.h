#ifndef rbc_ifem_diffusion_cut_cell_terms_h
#define rbc_ifem_diffusion_cut_cell_terms_h

#include <deal.II/fe/fe_interface_values.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/non_matching/fe_immersed_values.h>

#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * @name The weak-form terms of the cut-cell problems
   *
   * Each cut-cell problem (CutCellDiffusion, CutCellReaction) lists the
   * terms it is made of, as Lethe's assemblers do; each term adds its
   * contribution on one mesh cell (or one face) to the local matrix. The
   * unknowns are fields on either side of the membranes: field 0 the
   * plasma's P₀ (on the mesh cells that reach into the plasma), with a
   * reaction inside the cells also field 1 + c, P₁ of the red cells of
   * colour c.
   */
  /** @{ */

  /**
   * The shape functions of one mesh cell, sorted by the side of the
   * membranes their field belongs to: what each term needs to know.
   */
  struct CutCellShapes
  {
    /**
     * For each shape function: 0 the plasma's field, 1 the field of the red
     * cell this mesh cell reaches into, −1 neither (a field of another
     * colour, on which no term acts here).
     */
    std::vector<int> side;
    /// The sign of each shape function in the jump [P] = P₀ − P₁ across the
    /// membrane.
    std::vector<double> jump_sign;
  };

  /**
   * The coefficients of the Nitsche terms on the membrane in a cell:
   * the flux {αD ∂ₙP} = plasma_flux ∂ₙP₀ + cell_flux ∂ₙP₁ [µm²/(s Torr)]
   * and the penalty β on [P] [µm/(s Torr)]. For the membrane sink
   * (P₁ = 0) αD, 0 and γ_N k(k+1) αD/h.
   */
  struct MembraneCoupling
  {
    double plasma_flux;
    double cell_flux;
    double penalty;
  };

  /// The plasma's diffusion, (αD ∇P₀, ∇q₀) on the plasma part @p plasma of
  /// a cell, with αD = @p permeability.
  void
  add_plasma_diffusion(const FEValues<3>   &plasma,
                       const double         permeability,
                       const CutCellShapes &shapes,
                       FullMatrix<double>  &matrix);

  /// Diffusion and binding in the cytoplasm, (α_cD_c ∇P₁, ∇q₁) + (k P₁, q₁)
  /// on the part @p cytoplasm of a cell inside a red cell, with
  /// α_cD_c = @p permeability and k = @p rate.
  void
  add_cytoplasm_reaction(const FEValues<3>   &cytoplasm,
                         const double         permeability,
                         const double         rate,
                         const CutCellShapes &shapes,
                         FullMatrix<double>  &matrix);

  /**
   * The symmetric Nitsche terms on the membrane part @p membrane of a cell,
   *
   *   − ({αD ∂ₙP}, [q])_Γh − ([P], {αD ∂ₙq})_Γh + (β [P], [q])_Γh,
   *
   * with n the normal out of the plasma: P = 0 weakly for the membrane
   * sink, the two sides glued (Hansbo & Hansbo 2002) with a reaction.
   */
  void
  add_membrane_coupling(const NonMatching::FEImmersedSurfaceValues<3> &membrane,
                        const MembraneCoupling                        &coupling,
                        const CutCellShapes                           &shapes,
                        FullMatrix<double>                            &matrix);

  /**
   * The ghost penalty of field @p field on one face of a cut cell,
   * Σ_{j=1..min(k,2)} @p weight h^(2j−1) ([∂ₙʲP], [∂ₙʲq])_F with
   * weight = γ_g αD of the field, which bounds the condition number however
   * the membranes cut the cells (the third derivatives of Q3 are not
   * penalised). @p matrix has the face's interface DoFs.
   */
  void
  add_ghost_penalty(const FEInterfaceValues<3> &face,
                    const unsigned int          field,
                    const double                weight,
                    const double                h,
                    const unsigned int          degree,
                    FullMatrix<double>         &matrix);

  /** @} */
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_coupling_parameters_h
#define rbc_ifem_coupling_parameters_h

#include <deal.II/base/parameter_handler.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The forces between cells and between a cell and the capillary wall
   * (subsection "Cell interactions", doc/coupling.md). Each is a potential
   * per unit membrane area of the gap h between two surfaces, whose
   * pressure p(h) = -φ'(h) is what a parameter sets; a pressure of 0 turns
   * the force off. The initializers are the defaults (see
   * GeometryParameters).
   */
  struct InteractionParameters
  {
    /// Cell-cell repulsion: p(h) = p0 (Δ/h - 1)² for h < Δ.
    double repulsion_pressure = 10.; ///< p0 [pN/µm²]; 0: off
    double repulsion_range    = 0.3; ///< Δ [µm]
    /// Aggregation: Morse φ(h) = D_e [e^{2β(r0-h)} - 2 e^{β(r0-h)}].
    bool   aggregation          = false;
    double aggregation_energy   = 0.3;  ///< D_e [pN/µm = µJ/m²]
    double aggregation_width    = 3.84; ///< β [1/µm]
    double aggregation_distance = 0.49; ///< r0 [µm]
    double aggregation_cutoff   = 2.;   ///< beyond it φ = 0 [µm]
    /// Wall repulsion: p(d) = p0 (Δ/d - 1)² for a wall gap d < Δ.
    double wall_pressure = 10.; ///< p0 [pN/µm²]; 0: off
    double wall_range    = 0.3; ///< Δ [µm]

    void
    add_parameters(ParameterHandler &prm);

    /**
     * Throws InputError for a range of zero, or one that is not smaller
     * than the cell's @p cell_diameter (cell-cell), than the capillary's
     * @p capillary_radius (wall), or than half the @p segment_length (where
     * a cell would meet itself across a periodic end); and a Morse cutoff
     * that does not lie beyond its minimum.
     */
    void
    validate(const double cell_diameter,
             const double capillary_radius,
             const double segment_length) const;
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_coupling_contact_forces_h
#define rbc_ifem_coupling_contact_forces_h

#include <rbc_ifem/coupling/cell_force.h>
#include <rbc_ifem/coupling/cell_owners.h>
#include <rbc_ifem/coupling/parameters.h>
#include <rbc_ifem/membrane/membrane.h>

#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  class CellPopulation;

  /**
   * A potential of the gap h between two surfaces per unit area, φ(h)
   * [pN/µm], and its pressure p(h) = -φ'(h) [pN/µm²], with p > 0 pushing
   * the surfaces apart; zero beyond a cutoff.
   */
  class GapPotential
  {
  public:
    virtual ~GapPotential() = default;

    /// Beyond this gap φ = p = 0 [µm].
    virtual double
    cutoff() const = 0;

    /// φ(h) for 0 < h.
    virtual double
    energy(const double h) const = 0;

    /// p(h) and dp/dh for 0 < h < cutoff().
    virtual std::pair<double, double>
    pressure(const double h) const = 0;
    /// d²p/dh² for 0 < h < cutoff(): what the forces' derivative needs.
    virtual double
    pressure_curvature(const double h) const = 0;
  };

  /**
   * Repulsion: p(h) = p0 (Δ/h - 1)² for h < Δ, so p and p' vanish at the
   * range Δ and p grows without bound as h -> 0.
   */
  class RepulsivePotential : public GapPotential
  {
  public:
    RepulsivePotential(const double pressure_scale, const double range);

    double
    cutoff() const override;
    double
    energy(const double h) const override;
    std::pair<double, double>
    pressure(const double h) const override;
    double
    pressure_curvature(const double h) const override;

  private:
    const double p0;    ///< [pN/µm²]
    const double range; ///< Δ [µm]
  };

  /**
   * Aggregation: the Morse potential φ(h) = D_e [e^{2β(r0-h)} -
   * 2 e^{β(r0-h)}], the minimum -D_e at h = r0, attractive beyond it.
   */
  class MorsePotential : public GapPotential
  {
  public:
    MorsePotential(const double well_depth,
                   const double width,
                   const double distance,
                   const double cutoff);

    double
    cutoff() const override;
    double
    energy(const double h) const override;
    std::pair<double, double>
    pressure(const double h) const override;
    double
    pressure_curvature(const double h) const override;

  private:
    const double depth;    ///< D_e [pN/µm]
    const double beta;     ///< β [1/µm]
    const double distance; ///< r0 [µm]
    const double gap_cutoff;
  };

  /**
   * A GapPotential between the membranes of different cells, as a sum over
   * pairs of membrane points i, j of different cells,
   *
   *   E = Σ a_i a_j ψ(|x_i - x_j|),  ψ(r) = p(r) / (2π r),
   *
   * with a_i the reference area of point i (its lumped ∫ N_i dA0). The
   * pair density ψ is the one for which a flat membrane at a gap h from a
   * membrane point carries E per area Σ_j a_j ψ -> 2π ∫_h^∞ ψ(r) r dr =
   * φ(h): the membranes feel the gap potential whatever their mesh. ψ is
   * shifted so that it and ψ' vanish at the cutoff. Forces are the exact
   * -∂E/∂x, central and pairwise equal and opposite, so the total force
   * and torque vanish. Pairs are found in PointBins, never all pairs. In a
   * periodic segment (a @p period along x) a pair's separation is the
   * shortest across the ends, so cells interact through them. Each rank
   * bins the points of its own cells and of the cells whose boxes come
   * within the cutoff of them (CellBoxes::near_owned()), nothing else.
   */
  /// Two points of different cells near each other (MembraneInteraction).
  struct ClosePair
  {
    unsigned int ci, ni, cj, nj; ///< cell and node of each point
    Tensor<1, 3> separation;     ///< x_i - x_j, the shortest across the ends
    double       r;              ///< |x_i - x_j| [µm]
    double       weight;         ///< a_i a_j, their reference areas [µm⁴]
  };

  class MembraneInteraction : public CellForce
  {
  public:
    /// The @p potential between the @p membranes, across the ends of a
    /// segment with a @p period; each rank adds the forces on the cells of
    /// its @p owners (held by reference).
    MembraneInteraction(const std::vector<std::shared_ptr<Membrane>> &membranes,
                        std::unique_ptr<GapPotential>                 potential,
                        const std::optional<double>                  &period,
                        const CellOwners                             &owners);

    CellForceReport
    add_forces(const std::vector<Vector<double>> &positions,
               std::vector<Vector<double>>       &forces) const override;

    std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &positions) const override;

  private:
    /// ψ(r) and ψ'(r), shifted to vanish at the cutoff.
    std::pair<double, double>
    pair_density(const double r) const;
    std::pair<double, double>
    unshifted_pair_density(const double r) const;
    /// ψ''(r), the same shifted or not.
    double
    pair_density_curvature(const double r) const;
    /**
     * Call @p f(pair) for every ClosePair of points of different cells
     * closer than the cutoff at @p x.
     */
    template <typename PairFunction>
    void
    for_each_close_pair(const std::vector<Vector<double>> &x,
                        const PairFunction                &f) const;

    const std::vector<std::shared_ptr<Membrane>> &membranes;
    const std::unique_ptr<GapPotential>           potential;
    const std::optional<double>                   period;
    const CellOwners                             &owners;
    std::vector<std::vector<double>>              reference_areas;
    std::pair<double, double>                     at_cutoff;
  };

  /**
   * The capillary wall, a cylinder of radius R about the x axis, repels
   * every membrane point at the gap d = R - sqrt(y² + z²) with the energy
   * E = Σ a_i φ(d_i) of a RepulsivePotential. External: its total is part
   * of the held force. A point at or beyond the wall has infinite energy
   * (and the run's gap check stops it).
   */
  class WallRepulsion : public CellForce
  {
  public:
    /// Each rank adds the forces on the cells of its @p owners (held by
    /// reference).
    WallRepulsion(const std::vector<std::shared_ptr<Membrane>> &membranes,
                  const double                                  radius,
                  const RepulsivePotential                     &potential,
                  const CellOwners                             &owners);

    CellForceReport
    add_forces(const std::vector<Vector<double>> &positions,
               std::vector<Vector<double>>       &forces) const override;

    std::unique_ptr<CellForceStiffness>
    stiffness(const std::vector<Vector<double>> &positions) const override;

    /**
     * Bring every cell wider than the lumen into it: a wall that starts
     * just outside the cell closes in, by half the smallest gap at a time,
     * to the capillary's radius, and at each stage the membrane (its
     * reference shape unchanged) is relaxed to its static equilibrium
     * against it (find_equilibrium()). @p x, one Vector per cell, is
     * replaced by the squeezed positions. Each cell is squeezed by its
     * owner alone and the positions shared in one sum (collective), the
     * same as on one rank (to round-off where the membranes' work is
     * shared, with fewer cells than ranks: there every rank squeezes every
     * cell, together). Returns the number of stages of all cells.
     */
    unsigned int
    squeeze_into_lumen(std::vector<Vector<double>> &x) const;

  private:
    /// The energy and force of a wall of radius @p wall_radius on cell @p c.
    CellForceReport
    add_cell_forces(const unsigned int    c,
                    const double          wall_radius,
                    const Vector<double> &x,
                    Vector<double>       &forces) const;

    const std::vector<std::shared_ptr<Membrane>> &membranes;
    const double                                  radius;
    const RepulsivePotential                      potential;
    const CellOwners                             &owners;
    std::vector<std::vector<double>>              reference_areas;
  };

  /**
   * The potentials between cells that subsection Cell interactions switches
   * on: the repulsion and the aggregation's Morse attraction, each if on.
   */
  std::vector<std::unique_ptr<GapPotential>>
  cell_potentials(const InteractionParameters &parameters);

  /**
   * How far the forces between cells reach: the largest cutoff of
   * cell_potentials(), 0 with none [µm]. A rank's contact search sees the
   * cells within it of its own (its ghosts, RunReport::load_balance()).
   */
  double
  contact_reach(const InteractionParameters &parameters);

  /**
   * Add the forces of subsection Cell interactions to @p cells: the
   * repulsion between cells and the aggregation (if on), across the ends
   * of a segment with a @p period, and the repulsion from a capillary wall
   * of radius @p wall_radius (if there is one).
   */
  void
  add_interaction_forces(CellPopulation              &cells,
                         const InteractionParameters &parameters,
                         const std::optional<double>  wall_radius,
                         const std::optional<double>  period);
} // namespace rbc_ifem

#endif

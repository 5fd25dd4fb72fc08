#ifndef rbc_ifem_coupling_time_step_limit_h
#define rbc_ifem_coupling_time_step_limit_h

#include <rbc_ifem/membrane/parameters.h>

#include <limits>

namespace rbc_ifem
{
  /**
   * The time step limit of the explicit coupling [s]: a membrane wave of
   * wavenumber q relaxes in a Stokes fluid at the rate ω = E(q)/(4μq), E(q)
   * its stiffness per area, (K+G)q² in-plane and κq⁴ in bending; explicit
   * Euler needs ω Δt < 2. The shortest wave both the membrane points
   * (spacing s) and the Q2 fluid velocity (node spacing h/2) resolve has
   * q = π / max(s, h/2). Runs stay stable below about 0.7 of it
   * (doc/ifem.md).
   */
  struct CouplingTimeStepLimit
  {
    double in_plane = 0.;
    double bending  = 0.;
    /// The repulsion's, at the gaps the cells start at (include_contact()).
    double contact = std::numeric_limits<double>::infinity();
    double limit   = 0.; ///< the smallest of them
    /**
     * Not a stability limit but an accuracy one, which the automatic step
     * keeps to whatever the coupling (include_advection()): the step in
     * which a point at the run's speed moves a given distance.
     */
    double advective = std::numeric_limits<double>::infinity();

    CouplingTimeStepLimit(const double              viscosity,
                          const MembraneParameters &membrane,
                          const double              point_spacing,
                          const double              mesh_size);

    /**
     * Include the repulsion of stiffness @p stiffness = |dp/dh| per area
     * [pN/µm³] at the gap a membrane starts at: pressed like a spring, a
     * membrane relaxes at ω = k/(4μq), fastest in the longest wave a cell of
     * @p diameter holds, q = π/d, so that explicit Euler needs Δt < 8πμ/(d
     * k).
     */
    void
    include_contact(const double viscosity,
                    const double stiffness,
                    const double diameter);

    /// Set advective: the step in which a point at @p speed [µm/s] moves
    /// @p distance [µm] (none for a speed of 0).
    void
    include_advection(const double speed, const double distance);
  };
} // namespace rbc_ifem

#endif

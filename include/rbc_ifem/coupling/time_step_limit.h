#ifndef rbc_ifem_coupling_time_step_limit_h
#define rbc_ifem_coupling_time_step_limit_h

#include <rbc_ifem/membrane/parameters.h>

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
    double limit    = 0.; ///< the smaller of the two

    CouplingTimeStepLimit(const double              viscosity,
                          const MembraneParameters &membrane,
                          const double              point_spacing,
                          const double              mesh_size);
  };
} // namespace rbc_ifem

#endif

#ifndef rbc_ifem_reference_axisymmetric_sphere_in_tube_h
#define rbc_ifem_reference_axisymmetric_sphere_in_tube_h

namespace rbc_ifem
{
  /**
   * The drags on a rigid sphere on the axis of a circular tube in Stokes
   * flow, dimensionless, as Haberman & Sayre (1958) and Bohlin (1960) define
   * them (doc/validation.md, Section 2): a = λ R, viscosity μ.
   */
  struct SphereInTubeDrag
  {
    /// Towed through fluid at rest far away at speed U: F / (6π μ a U), "K".
    double towed_drag_factor;
    /// Held fixed in Poiseuille flow of centre-line speed U_c: F / (6π μ a
    /// U_c).
    double held_drag_factor;
    /// Freely suspended: its speed over the centre-line speed, U/U_c,
    /// which is held_drag_factor / towed_drag_factor (Stokes flow is linear).
    double       velocity_ratio;
    unsigned int n_cells; ///< cells of the meridian mesh
    unsigned int n_dofs;  ///< velocity and pressure unknowns
  };

  /**
   * An independent, body-fitted reference for the immersed sphere of
   * doc/validation.md: the same Stokes problem, solved on the meridian
   * half-plane (z, r) of the tube with the sphere's surface as a curved
   * boundary of the mesh, Taylor-Hood Q2-Q1 in cylindrical coordinates, and a
   * direct solver. It shares nothing with the immersed code but deal.II.
   *
   * The meridian mesh covers z in [-L, L], r in [0, R] minus the half disc of
   * radius λR at the origin: four cells around the half disc (the sphere is a
   * polar manifold, the cells blend to the square [-R, R] x [0, R] by
   * transfinite interpolation) and cells of about R x R out to the ends,
   * refined @p n_refinements times. The force on the sphere is the consistent
   * one, the residual of the momentum equations at the sphere's velocity
   * unknowns, which converges faster than the stress integrated on the
   * surface.
   *
   * @p lambda must lie in (0, 0.9], @p half_length at least 2 (in units of R:
   * the disturbance of the sphere decays like exp(-4.5 z / R)).
   */
  SphereInTubeDrag
  axisymmetric_sphere_in_tube(const double       lambda,
                              const unsigned int n_refinements,
                              const double       half_length = 4.);
} // namespace rbc_ifem

#endif

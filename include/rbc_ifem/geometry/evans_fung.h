#ifndef rbc_ifem_geometry_evans_fung_h
#define rbc_ifem_geometry_evans_fung_h

#include <rbc_ifem/geometry/cell_placement.h>
#include <rbc_ifem/geometry/parameters.h>

#include <deal.II/grid/manifold.h>
#include <deal.II/grid/manifold_lib.h>

#include <array>
#include <memory>
#include <string>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The Evans-Fung biconcave shape of a resting red cell (doc/design.md,
   * "Membrane"): in a frame with the symmetry axis along z,
   *
   *   z(r) = ±0.5 R sqrt(1 - ρ²) (a0 + a1 ρ² + a2 ρ⁴),  ρ = r/R,
   *
   * with a0 = 0.207, a1 = 2.002, a2 = -1.123 and R half the diameter for
   * the red cell (red_cell). The same family holds the sphere of radius R:
   * a0 = 2, a1 = a2 = 0 (sphere), the capsule of the validation runs.
   *
   * The shape is the image of the unit sphere under the smooth map
   *
   *   F(s) = (R s_x, R s_y, 0.5 R s_z g(s_z)),  g(t) = a0 + a1 (1-t²) + a2
   * (1-t²)²,
   *
   * because on the sphere ρ² = s_x² + s_y² = 1 - s_z². Meshing the sphere and
   * mapping it with F gives a surface mesh whose refinement converges to the
   * exact shape (see EvansFungManifold).
   */
  class EvansFungShape
  {
  public:
    /// The coefficients a0, a1, a2 of a shape of the family.
    using Coefficients = std::array<double, 3>;
    static constexpr Coefficients red_cell{{0.207, 2.002, -1.123}};
    static constexpr Coefficients sphere{{2., 0., 0.}};

    explicit EvansFungShape(const double        diameter,
                            const Coefficients &coefficients = red_cell);

    /// The shape of subsection Cells: its Shape (red_cell or sphere) and
    /// Diameter.
    static EvansFungShape
    of(const CellParameters &cells);

    double
    radius() const;

    /// Half thickness z(r) of the profile at distance r from the axis.
    double
    half_thickness(const double r) const;

    /// Map F from the unit sphere to the shape, in the local frame.
    Point<3>
    from_sphere(const Point<3> &s) const;

    /// The derivative of F at @p s (a 3x3 matrix).
    Tensor<2, 3>
    from_sphere_gradient(const Point<3> &s) const;

    /// The inverse of F for a point on the shape, in the local frame.
    Point<3>
    to_sphere(const Point<3> &x) const;

    /**
     * The exact area [µm²] and enclosed volume [µm³] of the shape, by 1-D
     * Gauss quadrature of the profile (to round-off): as a curve in
     * t = cos(polar angle), r(t) = R sqrt(1 - t²) and z(t) = 0.5 R t g(t),
     * A = ∫ 2π r |(r', z')| dt, with r |(r', z')| = sqrt(R⁴t² + r²z'²)
     * smooth, and V = ∫ π r² z' dt (signed, so the dimples count).
     */
    double
    exact_area() const;
    double
    exact_volume() const;

    /**
     * The largest extent of a cell with the given @p placement along
     * @p direction, measured from its centre (the support function of the
     * shape), found by a search over the parametrisation to round-off.
     */
    double
    extent(const CellPlacement &placement, const Tensor<1, 3> &direction) const;

    /// The largest distance from the x axis (the capillary's) of a cell
    /// with the given @p placement, by the same search as extent().
    double
    farthest_from_axis(const CellPlacement &placement) const;

    /// Whether the point @p x lies strictly inside the cell placed so.
    bool
    contains(const CellPlacement &placement, const Point<3> &x) const;

  private:
    /// g(t) of the class documentation, and its derivative.
    double
    g(const double t) const;
    double
    dg(const double t) const;

    /**
     * Maximise @p f over the surface of a placed cell: a grid over the
     * polar and azimuthal sphere angles, then successive zooms around the
     * best point.
     */
    template <typename Function>
    double
    maximize_over_surface(const CellPlacement &placement,
                          const Function      &f) const;

    const double       R;
    const Coefficients a;
  };


  /**
   * The manifold of one placed Evans-Fung cell surface, for a
   * Triangulation<2,3>: new points are the image under F of the spherical
   * (geodesic) new points of the preimages on the unit sphere. Since F is
   * smooth and one-to-one, refinement converges to the exact shape.
   */
  class EvansFungManifold : public Manifold<2, 3>
  {
  public:
    EvansFungManifold(const EvansFungShape &shape,
                      const CellPlacement  &placement);

    std::unique_ptr<Manifold<2, 3>>
    clone() const override;

    Point<3>
    get_intermediate_point(const Point<3> &p1,
                           const Point<3> &p2,
                           const double    w) const override;

    Point<3>
    get_new_point(const ArrayView<const Point<3>> &surrounding_points,
                  const ArrayView<const double>   &weights) const override;

    Tensor<1, 3>
    get_tangent_vector(const Point<3> &x1, const Point<3> &x2) const override;

    /// Global position of the sphere point @p s, and its preimage.
    Point<3>
    push_forward(const Point<3> &s) const;
    Point<3>
    pull_back(const Point<3> &x) const;

  private:
    const EvansFungShape          shape;
    const CellPlacement           placement;
    const Tensor<2, 3>            rotation;
    const SphericalManifold<2, 3> sphere;
  };
} // namespace rbc_ifem

#endif

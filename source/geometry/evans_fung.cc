#include <rbc_ifem/geometry/evans_fung.h>

#include <deal.II/base/quadrature_lib.h>

#include <cmath>
#include <vector>

namespace rbc_ifem
{
  EvansFungShape::EvansFungShape(const double        diameter,
                                 const Coefficients &coefficients)
    : R(diameter / 2.)
    , a(coefficients)
  {}

  EvansFungShape
  EvansFungShape::of(const CellParameters &cells)
  {
    return EvansFungShape(cells.diameter,
                          cells.shape == ReferenceShape::sphere ? sphere :
                                                                  red_cell);
  }

  double
  EvansFungShape::radius() const
  {
    return R;
  }

  double
  EvansFungShape::g(const double t) const
  {
    const double u = 1. - t * t;
    return a[0] + a[1] * u + a[2] * u * u;
  }

  double
  EvansFungShape::dg(const double t) const
  {
    const double u = 1. - t * t;
    return -2. * t * (a[1] + 2. * a[2] * u);
  }

  double
  EvansFungShape::half_thickness(const double r) const
  {
    const double rho2 = std::min(1., (r / R) * (r / R));
    return 0.5 * R * std::sqrt(1. - rho2) *
           (a[0] + a[1] * rho2 + a[2] * rho2 * rho2);
  }

  Point<3>
  EvansFungShape::from_sphere(const Point<3> &s) const
  {
    return Point<3>(R * s[0], R * s[1], 0.5 * R * s[2] * g(s[2]));
  }

  Tensor<2, 3>
  EvansFungShape::from_sphere_gradient(const Point<3> &s) const
  {
    Tensor<2, 3> d;
    d[0][0] = R;
    d[1][1] = R;
    d[2][2] = 0.5 * R * (g(s[2]) + s[2] * dg(s[2]));
    return d;
  }

  Point<3>
  EvansFungShape::to_sphere(const Point<3> &x) const
  {
    const double sx   = x[0] / R;
    const double sy   = x[1] / R;
    const double rho2 = sx * sx + sy * sy;
    double       t    = std::copysign(std::sqrt(std::max(0., 1. - rho2)), x[2]);

    // Near the rim (|t| small) the square root loses accuracy; there
    // z = 0.5 R t g(t) is strictly monotone in t (its derivative is > 0.9
    // for t² < 1/4), so a few Newton steps on z recover t to round-off.
    if (t * t < 0.25)
      for (unsigned int it = 0; it < 8; ++it)
        {
          const double residual = 0.5 * R * t * g(t) - x[2];
          const double slope    = 0.5 * R * (g(t) + t * dg(t));
          t -= residual / slope;
        }
    return Point<3>(sx, sy, t);
  }

  template <typename Function>
  double
  EvansFungShape::maximize_over_surface(const CellPlacement &placement,
                                        const Function      &f) const
  {
    const Tensor<2, 3> q     = placement.rotation();
    const auto         value = [&](const double theta, const double phi) {
      const Point<3> s(std::sin(theta) * std::cos(phi),
                       std::sin(theta) * std::sin(phi),
                       std::cos(theta));
      return f(placement.center + q * from_sphere(s));
    };

    // A coarse grid over (theta, phi), then zooms around the best point; the
    // functions maximised are smooth, so each zoom gains a factor 16 in the
    // value's accuracy.
    double best = value(0., 0.), best_theta = 0., best_phi = 0.;
    double d_theta = numbers::PI / 64., d_phi = 2. * numbers::PI / 128.;
    int    half_width_theta = 32, half_width_phi = 64;
    double centre_theta = numbers::PI / 2., centre_phi = numbers::PI;
    for (unsigned int zoom = 0; zoom < 8; ++zoom)
      {
        for (int i = -half_width_theta; i <= half_width_theta; ++i)
          for (int j = -half_width_phi; j <= half_width_phi; ++j)
            {
              const double theta =
                std::clamp(centre_theta + i * d_theta, 0., numbers::PI);
              const double phi = centre_phi + j * d_phi;
              const double v   = value(theta, phi);
              if (v > best)
                {
                  best       = v;
                  best_theta = theta;
                  best_phi   = phi;
                }
            }
        centre_theta     = best_theta;
        centre_phi       = best_phi;
        half_width_theta = half_width_phi = 4;
        d_theta /= 4.;
        d_phi /= 4.;
      }
    return best;
  }

  double
  EvansFungShape::extent(const CellPlacement &placement,
                         const Tensor<1, 3>  &direction) const
  {
    const Tensor<1, 3> e = direction / direction.norm();
    return maximize_over_surface(placement, [&](const Point<3> &x) {
      return (x - placement.center) * e;
    });
  }

  double
  EvansFungShape::farthest_from_axis(const CellPlacement &placement) const
  {
    return maximize_over_surface(placement, [](const Point<3> &x) {
      return std::hypot(x[1], x[2]);
    });
  }

  bool
  EvansFungShape::contains(const CellPlacement &placement,
                           const Point<3>      &x) const
  {
    // In the local frame the shape is |z| < z(r) for r < R (z(r) > 0).
    const Tensor<1, 3> local =
      transpose(placement.rotation()) * (x - placement.center);
    const double r = std::hypot(local[0], local[1]);
    return r < R && std::abs(local[2]) < half_thickness(r);
  }

  EvansFungManifold::EvansFungManifold(const EvansFungShape &shape,
                                       const CellPlacement  &placement)
    : shape(shape)
    , placement(placement)
    , rotation(placement.rotation())
    , sphere(Point<3>())
  {}

  std::unique_ptr<Manifold<2, 3>>
  EvansFungManifold::clone() const
  {
    return std::make_unique<EvansFungManifold>(shape, placement);
  }

  Point<3>
  EvansFungManifold::push_forward(const Point<3> &s) const
  {
    return placement.center + rotation * shape.from_sphere(s);
  }

  Point<3>
  EvansFungManifold::pull_back(const Point<3> &x) const
  {
    return shape.to_sphere(
      Point<3>(transpose(rotation) * (x - placement.center)));
  }

  Point<3>
  EvansFungManifold::get_intermediate_point(const Point<3> &p1,
                                            const Point<3> &p2,
                                            const double    w) const
  {
    return push_forward(
      sphere.get_intermediate_point(pull_back(p1), pull_back(p2), w));
  }

  Point<3>
  EvansFungManifold::get_new_point(
    const ArrayView<const Point<3>> &surrounding_points,
    const ArrayView<const double>   &weights) const
  {
    std::vector<Point<3>> on_sphere(surrounding_points.size());
    for (unsigned int i = 0; i < on_sphere.size(); ++i)
      on_sphere[i] = pull_back(surrounding_points[i]);
    return push_forward(
      sphere.get_new_point(make_array_view(on_sphere), weights));
  }

  Tensor<1, 3>
  EvansFungManifold::get_tangent_vector(const Point<3> &x1,
                                        const Point<3> &x2) const
  {
    const Point<3> s1 = pull_back(x1);
    return rotation * (shape.from_sphere_gradient(s1) *
                       sphere.get_tangent_vector(s1, pull_back(x2)));
  }
  namespace
  {
    /// ∫ over t in [-1, 1] of f(t, r², z'(t)) for the profile of @p shape.
    template <typename Integrand>
    double
    integrate_profile(const EvansFungShape &shape, const Integrand &f)
    {
      const double R = shape.radius();
      // z(t) = 0.5 R t g(t) is the z component of F on the axis s = (0, 0, t).
      const auto z_prime = [&](const double t) {
        return shape.from_sphere_gradient(Point<3>(0., 0., t))[2][2];
      };
      const QGauss<1> gauss(60);
      double          sum = 0.;
      for (unsigned int q = 0; q < gauss.size(); ++q)
        for (const double sign : {-1., 1.})
          {
            const double t = sign * gauss.point(q)[0];
            sum += f(t, R * R * (1. - t * t), z_prime(t)) * gauss.weight(q);
          }
      return sum;
    }
  } // namespace

  double
  EvansFungShape::exact_area() const
  {
    const double R = radius();
    return integrate_profile(
      *this, [R](const double t, const double r2, const double zp) {
        return 2. * numbers::PI *
               std::sqrt(R * R * R * R * t * t + r2 * zp * zp);
      });
  }

  double
  EvansFungShape::exact_volume() const
  {
    return integrate_profile(
      *this, [](const double, const double r2, const double zp) {
        return numbers::PI * r2 * zp;
      });
  }
} // namespace rbc_ifem

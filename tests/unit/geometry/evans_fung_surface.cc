// The Evans-Fung membrane mesh: its vertices lie on the exact shape, and its
// area and enclosed volume converge to the exact values (EvansFungShape::
// exact_area(), exact_volume(): 1-D Gauss quadrature of the profile z(r)).
// Prints the errors and the observed convergence orders for the linear mapping
// and for the quadratic one the program uses.

#include <rbc_ifem/geometry/cell_surface.h>

#include "check.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_tools.h>

using namespace rbc_ifem;

namespace
{
  /// An observed order for the table, "-" where there is none yet.
  std::string
  order_text(const double order)
  {
    if (std::isnan(order))
      return "-";
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << order;
    return s.str();
  }

} // namespace

int
main()
{
  Checker              check;
  const double         diameter = 7.5;
  const EvansFungShape shape(diameter);
  const CellPlacement  placement{Point<3>(1., -0.5, 2.),
                                Tensor<1, 3>({1., 1., 0.})};
  const struct
  {
    double area, volume;
  } exact{shape.exact_area(), shape.exact_volume()};

  std::cout << std::setprecision(10) << "exact area " << exact.area
            << " µm², exact volume " << exact.volume << " µm³\n";
  // The classic cell (R = 3.91 µm) has A ≈ 135 µm², V ≈ 94 µm³; ours scales.
  const double scale = 3.91 / 3.75;
  check.near("area scaled to R = 3.91 µm",
             exact.area * scale * scale,
             135.,
             1.5);
  check.near("volume scaled to R = 3.91 µm",
             exact.volume * scale * scale * scale,
             94.,
             1.5);

  // Every vertex of a refined mesh lies on the shape: F(F⁻¹(x)) = x with a
  // preimage on the unit sphere.
  {
    Triangulation<2, 3> surface;
    create_cell_surface(surface, shape, placement, 4);
    const EvansFungManifold manifold(shape, placement);
    double                  worst = 0.;
    for (const Point<3> &x : surface.get_vertices())
      {
        const Point<3> s = manifold.pull_back(x);
        worst            = std::max({worst,
                                     std::abs(s.norm() - 1.),
                                     manifold.push_forward(s).distance(x)});
      }
    check.at_most("largest distance of a vertex from the shape [µm]",
                  worst,
                  1e-12);
  }

  for (const unsigned int degree : {1u, 2u})
    {
      std::cout
        << "MappingQ(" << degree << ")\n"
        << "  refinements  cells   area error   order   volume error   order\n";
      const MappingQ<2, 3> mapping(degree);
      double               area_error = 0., volume_error = 0.;
      double area_order = std::nan(""), volume_order = std::nan("");
      for (unsigned int refinements = 1; refinements <= 5; ++refinements)
        {
          Triangulation<2, 3> surface;
          create_cell_surface(surface, shape, placement, refinements);
          const SurfaceMeasures m = measure_surface(surface, mapping);
          const double e_a        = std::abs(m.area - exact.area) / exact.area;
          const double e_v = std::abs(m.volume - exact.volume) / exact.volume;
          if (refinements > 1)
            {
              area_order   = std::log2(area_error / e_a);
              volume_order = std::log2(volume_error / e_v);
            }
          area_error   = e_a;
          volume_error = e_v;
          std::cout << std::setw(13) << refinements << std::setw(7)
                    << surface.n_active_cells() << std::scientific
                    << std::setprecision(3) << std::setw(13) << e_a
                    << std::setw(8) << order_text(area_order) << std::setw(15)
                    << e_v << std::setw(8) << order_text(volume_order) << '\n';
          if (refinements == 5)
            check.near("centroid distance from the placed centre [µm]",
                       m.centroid.distance(placement.center),
                       0.,
                       1e-6);
        }
      const double expected_order = 2. * degree;
      check.at_least("observed area order, MappingQ(" + std::to_string(degree) +
                       ")",
                     area_order,
                     expected_order - 0.3);
      check.at_least("observed volume order, MappingQ(" +
                       std::to_string(degree) + ")",
                     volume_order,
                     expected_order - 0.3);
      check.at_most("relative area error at 5 refinements",
                    area_error,
                    degree == 1 ? 2e-3 : 5e-7);
      check.at_most("relative volume error at 5 refinements",
                    volume_error,
                    degree == 1 ? 2e-3 : 5e-7);
    }

  // The sphere of the family (a0 = 2, a1 = a2 = 0), stretched to the
  // ellipsoid of semi-axes 4, 2, 1 µm and turned by 30° about z: its second
  // moment is V/5 Q diag(16, 4, 1) Qᵀ, so in the x-y plane L = 4, B = 2,
  // D = 1/3 and the long axis is inclined by 30°.
  {
    const EvansFungShape sphere(2., EvansFungShape::sphere);
    check.near("unit sphere: exact area",
               sphere.exact_area(),
               4. * numbers::PI,
               1e-12);
    check.near("unit sphere: exact volume",
               sphere.exact_volume(),
               4. * numbers::PI / 3.,
               1e-12);

    Triangulation<2, 3> surface;
    create_cell_surface(surface,
                        sphere,
                        CellPlacement{Point<3>(), Tensor<1, 3>({0., 0., 1.})},
                        5);
    const double angle = numbers::PI / 6.;
    GridTools::transform(
      [angle](const Point<3> &p) {
        const Point<3> e(4. * p[0], 2. * p[1], p[2]);
        return Point<3>(std::cos(angle) * e[0] - std::sin(angle) * e[1],
                        std::sin(angle) * e[0] + std::cos(angle) * e[1],
                        e[2]);
      },
      surface);
    surface.set_all_manifold_ids(numbers::flat_manifold_id);
    const SurfaceMeasures   m = measure_surface(surface, MappingQ<2, 3>(1));
    const ShearPlaneEllipse ellipse = shear_plane_ellipse(m.second_moment);
    check.near("ellipsoid: volume (bilinear mesh)",
               m.volume,
               4. * numbers::PI / 3. * 8.,
               0.05);
    check.near("ellipsoid: second moment zz / (V/5)",
               m.second_moment[2][2] / (m.volume / 5.),
               1.,
               2e-3);
    check.near("ellipsoid: Taylor deformation (L - B)/(L + B)",
               ellipse.taylor_deformation,
               1. / 3.,
               1e-3);
    check.near("ellipsoid: inclination [rad]",
               ellipse.inclination,
               angle,
               1e-3);
  }
  return check.exit_code();
}

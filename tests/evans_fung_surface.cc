// The Evans-Fung membrane mesh: its vertices lie on the exact shape, and its
// area and enclosed volume converge to the exact values (EvansFungShape::
// exact_area(), exact_volume(): 1-D Gauss quadrature of the profile z(r)). Prints the errors
// and the observed convergence orders for the linear mapping and for the
// quadratic one the program uses.

#include <rbc_ifem/cell_surface.h>

#include <deal.II/base/quadrature_lib.h>

#include "check.h"

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
  const CellPlacement  placement{Point<3>(1., -0.5, 2.), Tensor<1, 3>({1., 1., 0.})};
  const struct
  {
    double area, volume;
  } exact{shape.exact_area(), shape.exact_volume()};

  std::cout << std::setprecision(10) << "exact area " << exact.area
            << " µm², exact volume " << exact.volume << " µm³\n";
  // The classic cell (R = 3.91 µm) has A ≈ 135 µm², V ≈ 94 µm³; ours scales.
  const double scale = 3.91 / 3.75;
  check.near("area scaled to R = 3.91 µm", exact.area * scale * scale, 135., 1.5);
  check.near("volume scaled to R = 3.91 µm", exact.volume * scale * scale * scale, 94., 1.5);

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
        worst = std::max({worst, std::abs(s.norm() - 1.), manifold.push_forward(s).distance(x)});
      }
    check.at_most("largest distance of a vertex from the shape [µm]", worst, 1e-12);
  }

  for (const unsigned int degree : {1u, 2u})
    {
      std::cout << "MappingQ(" << degree << ")\n"
                << "  refinements  cells   area error   order   volume error   order\n";
      const MappingQ<2, 3> mapping(degree);
      double area_error = 0., volume_error = 0.;
      double area_order = std::nan(""), volume_order = std::nan("");
      for (unsigned int refinements = 1; refinements <= 5; ++refinements)
        {
          Triangulation<2, 3> surface;
          create_cell_surface(surface, shape, placement, refinements);
          const SurfaceMeasures m = measure_surface(surface, mapping);
          const double          e_a = std::abs(m.area - exact.area) / exact.area;
          const double          e_v = std::abs(m.volume - exact.volume) / exact.volume;
          if (refinements > 1)
            {
              area_order   = std::log2(area_error / e_a);
              volume_order = std::log2(volume_error / e_v);
            }
          area_error   = e_a;
          volume_error = e_v;
          std::cout << std::setw(13) << refinements << std::setw(7) << surface.n_active_cells()
                    << std::scientific << std::setprecision(3) << std::setw(13) << e_a
                    << std::setw(8) << order_text(area_order) << std::setw(15) << e_v
                    << std::setw(8) << order_text(volume_order) << '\n';
          if (refinements == 5)
            check.near("centroid distance from the placed centre [µm]",
                       m.centroid.distance(placement.center), 0., 1e-6);
        }
      const double expected_order = 2. * degree;
      check.at_least("observed area order, MappingQ(" + std::to_string(degree) + ")",
                     area_order, expected_order - 0.3);
      check.at_least("observed volume order, MappingQ(" + std::to_string(degree) + ")",
                     volume_order, expected_order - 0.3);
      check.at_most("relative area error at 5 refinements", area_error, degree == 1 ? 2e-3 : 5e-7);
      check.at_most("relative volume error at 5 refinements", volume_error, degree == 1 ? 2e-3 : 5e-7);
    }
  return check.exit_code();
}

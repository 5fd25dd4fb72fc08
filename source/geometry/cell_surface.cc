#include <rbc_ifem/geometry/cell_surface.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/rtree.h>

namespace rbc_ifem
{
  void
  create_cell_surface(Triangulation<2, 3>  &surface,
                      const EvansFungShape &shape,
                      const CellPlacement  &placement,
                      const unsigned int    n_refinements)
  {
    const EvansFungManifold manifold(shape, placement);

    surface.clear();
    GridGenerator::hyper_sphere(surface, Point<3>(), 1.);
    GridTools::transform(
      [&](const Point<3> &s) { return manifold.push_forward(s); }, surface);
    surface.set_all_manifold_ids(0);
    surface.set_manifold(0, manifold);
    surface.refine_global(n_refinements);
  }

  namespace
  {
    /// Mapped quadrature points (and normals, JxW) of every surface cell.
    template <typename Worker>
    void
    for_each_quadrature_point(const Triangulation<2, 3> &surface,
                              const MappingQ<2, 3>      &mapping,
                              const Quadrature<2>       &quadrature,
                              const Worker              &worker)
    {
      const FE_Nothing<2, 3> fe;
      FEValues<2, 3>         fe_values(mapping,
                               fe,
                               quadrature,
                               update_quadrature_points |
                                 update_normal_vectors | update_JxW_values);
      for (const auto &cell : surface.active_cell_iterators())
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            worker(fe_values.quadrature_point(q),
                   fe_values.normal_vector(q),
                   fe_values.JxW(q));
        }
    }
  } // namespace

  SurfaceMeasures
  measure_surface(const Triangulation<2, 3> &surface,
                  const MappingQ<2, 3>      &mapping)
  {
    // Integrate about a point near the surface to keep round-off small.
    Point<3> c;
    for (const Point<3> &v : surface.get_vertices())
      c += v / surface.n_vertices();
    SurfaceMeasures m;
    Tensor<1, 3>    first_moment;
    Tensor<2, 3>    second_moment; // about c
    for_each_quadrature_point(
      surface,
      mapping,
      QGauss<2>(mapping.get_degree() + 2),
      [&](const Point<3> &x, const Tensor<1, 3> &n, const double JxW) {
        const Tensor<1, 3> y = x - c;
        m.area += JxW;
        m.volume += y * n * JxW / 3.;
        for (unsigned int d = 0; d < 3; ++d)
          first_moment[d] += 0.5 * y[d] * y[d] * n[d] * JxW;
        second_moment += outer_product(y, y) * (y * n) * JxW / 5.;
      });
    m.centroid           = c + first_moment / m.volume;
    const Tensor<1, 3> d = m.centroid - c;
    m.second_moment      = second_moment - m.volume * outer_product(d, d);
    return m;
  }

  ShearPlaneEllipse
  shear_plane_ellipse(const Tensor<2, 3> &S)
  {
    const double mean = (S[0][0] + S[1][1]) / 2.;
    const double half_difference =
      std::hypot((S[0][0] - S[1][1]) / 2., S[0][1]);
    const double L = std::sqrt(mean + half_difference),
                 B = std::sqrt(std::max(0., mean - half_difference));
    // The long axis at ±π/2 (a cell facing the flow) is one axis: an
    // off-diagonal of round-off size must not pick the sign, or the same
    // cell reads -π/2 in one run and π/2 in the next. Counted as zero, it
    // gives π/2, the end of the range (-π/2, π/2] that belongs to it.
    const double off_diagonal =
      std::abs(S[0][1]) <= 1e-12 * (std::abs(S[0][0]) + std::abs(S[1][1])) ?
        0. :
        S[0][1];
    return {(L - B) / (L + B),
            0.5 * std::atan2(2. * off_diagonal, S[0][0] - S[1][1])};
  }

  Clearance
  measure_clearance(const std::vector<const Triangulation<2, 3> *> &surfaces,
                    const MappingQ<2, 3>                           &mapping,
                    const double capillary_radius)
  {
    namespace bgi = boost::geometry::index;

    std::vector<std::vector<Point<3>>> clouds(surfaces.size());
    Clearance                          clearance;
    for (unsigned int i = 0; i < surfaces.size(); ++i)
      {
        clouds[i] = surfaces[i]->get_vertices();
        for_each_quadrature_point(*surfaces[i],
                                  mapping,
                                  QGauss<2>(3),
                                  [&](const Point<3> &x,
                                      const Tensor<1, 3> &,
                                      const double) {
                                    clouds[i].push_back(x);
                                  });
        for (const Point<3> &x : clouds[i])
          clearance.min_wall_gap =
            std::min(clearance.min_wall_gap,
                     capillary_radius - std::hypot(x[1], x[2]));
      }

    for (unsigned int i = 0; i < clouds.size(); ++i)
      {
        const auto tree = pack_rtree(clouds[i]);
        for (unsigned int j = i + 1; j < clouds.size(); ++j)
          for (const Point<3> &x : clouds[j])
            for (const Point<3> &nearest :
                 tree | bgi::adaptors::queried(bgi::nearest(x, 1)))
              if (x.distance(nearest) < clearance.min_cell_gap)
                {
                  clearance.min_cell_gap  = x.distance(nearest);
                  clearance.closest_cells = {i, j};
                }
      }
    return clearance;
  }
} // namespace rbc_ifem

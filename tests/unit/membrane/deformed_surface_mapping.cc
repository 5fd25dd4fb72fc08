// The curved surface the uptake solve sees on a deformed membrane
// (DeformedSurfaceMapping), on a sphere of radius 3 µm, for membranes of
// degree 1 and 2:
//
// - undeformed (x = X), it is the reference MappingQ of degree 2 on the
//   sphere's manifold, at points all over every cell;
// - displaced by an affine map of X, it is the reference shape displaced by
//   that map (which checks the order of the support points);
// - at randomly perturbed positions it passes through every vertex.

#include <rbc_ifem/membrane/deformed_surface_mapping.h>
#include <rbc_ifem/membrane/membrane.h>

#include "check.h"

#include <deal.II/grid/grid_generator.h>

#include <functional>
#include <random>

using namespace rbc_ifem;

namespace
{
  /// The largest distance between @p mapping's image of the points of a
  /// 4×4 grid in every cell of @p surface and @p expected(reference cell, ξ).
  double
  largest_gap(const Mapping<2, 3>       &mapping,
              const Triangulation<2, 3> &surface,
              const Triangulation<2, 3> &reference,
              const std::function<
                Point<3>(const Triangulation<2, 3>::active_cell_iterator &,
                         const Point<2> &)> &expected)
  {
    double gap            = 0.;
    auto   reference_cell = reference.begin_active();
    for (const auto &cell : surface.active_cell_iterators())
      {
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int j = 0; j < 4; ++j)
            {
              const Point<2> xi(0.1 + 0.27 * i, 0.05 + 0.3 * j);
              gap =
                std::max(gap,
                         mapping.transform_unit_to_real_cell(cell, xi).distance(
                           expected(reference_cell, xi)));
            }
        ++reference_cell;
      }
    return gap;
  }

  void
  check_degree(Checker &check, const unsigned int degree)
  {
    std::cout << "Membrane of degree " << degree << ":\n";
    Triangulation<2, 3> sphere;
    GridGenerator::hyper_sphere(sphere, Point<3>(), 3.);
    sphere.refine_global(2);
    MembraneParameters parameters;
    parameters.degree = degree;
    const Membrane        membrane(sphere, parameters);
    const MappingQ<2, 3>  reference_mapping(2);
    const Vector<double> &X = membrane.reference_positions();
    Triangulation<2, 3>   surface;

    const auto mapped = [&](const Vector<double> &x) {
      membrane.build_surface(x, surface);
      return DeformedSurfaceMapping({&surface}, {&membrane}, {x});
    };

    const auto reference_point = [&](const auto &cell, const Point<2> &xi) {
      return reference_mapping.transform_unit_to_real_cell(cell, xi);
    };
    check.at_most("undeformed: largest distance from the reference MappingQ "
                  "[µm]",
                  largest_gap(mapped(X), surface, sphere, reference_point),
                  1e-12);

    // x = X + A X + b: the membrane's element interpolates A X + b exactly,
    // so the surface is the reference plus A (X interpolated at degree
    // k: MappingQ(k) on the sphere) + b, wherever the support points lie.
    const Tensor<2, 3> A(
      {{0.1, -0.3, 0.2}, {0.05, 0.2, -0.1}, {0.3, 0., -0.2}});
    const Tensor<1, 3>   b({0.3, -1.2, 2.5});
    const MappingQ<2, 3> interpolated_X(degree);
    Vector<double>       affine(X);
    for (const auto &node : membrane.nodes())
      {
        const Point<3> y(X[node[0]], X[node[1]], X[node[2]]);
        for (unsigned int d = 0; d < 3; ++d)
          affine[node[d]] += (A * y + b)[d];
      }
    check.at_most(
      "affine displacement: largest distance from the reference + A X + b "
      "[µm]",
      largest_gap(mapped(affine),
                  surface,
                  sphere,
                  [&](const auto &cell, const Point<2> &xi) {
                    const Point<3> y =
                      interpolated_X.transform_unit_to_real_cell(cell, xi);
                    return reference_point(cell, xi) + A * y + b;
                  }),
      1e-12);

    std::mt19937                           random(7);
    std::uniform_real_distribution<double> uniform(-0.2, 0.2);
    Vector<double>                         perturbed(X);
    for (auto &entry : perturbed)
      entry += uniform(random);
    const DeformedSurfaceMapping mapping    = mapped(perturbed);
    double                       vertex_gap = 0.;
    for (const auto &cell : surface.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        vertex_gap = std::max(vertex_gap,
                              mapping
                                .transform_unit_to_real_cell(
                                  cell, GeometryInfo<2>::unit_cell_vertex(v))
                                .distance(cell->vertex(v)));
    check.at_most("perturbed: largest distance from a vertex [µm]",
                  vertex_gap,
                  1e-12);
  }
} // namespace

int
main()
{
  Checker check;
  check_degree(check, 1);
  check_degree(check, 2);
  return check.exit_code();
}

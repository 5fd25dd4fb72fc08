#include <rbc_ifem/diffusion/membrane_distance.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/rtree.h>

#include <boost/container_hash/hash.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rbc_ifem
{
  namespace
  {
    /// Samples per patch edge for the R-tree: the nodes and the midpoints
    /// between them, so the nearest sample is a good Gauss-Newton start.
    unsigned int
    n_samples_1d(const unsigned int degree)
    {
      return 2 * degree + 1;
    }

    /// Nearest samples whose patches are tried for each query.
    constexpr unsigned int n_candidates = 8;

    /// The signed solid angle of the triangle a, b, c (its vertices seen
    /// from the viewpoint), positive when its normal (b - a) × (c - a)
    /// points away from the viewpoint.
    double
    solid_angle(const Tensor<1, 3> &a,
                const Tensor<1, 3> &b,
                const Tensor<1, 3> &c)
    {
      const double la = a.norm(), lb = b.norm(), lc = c.norm();
      return 2. * std::atan2(a * cross_product_3d(b, c),
                             la * lb * lc + (a * b) * lc + (a * c) * lb +
                               (b * c) * la);
    }

    /// The largest mapping degree the fixed-size evaluation supports.
    constexpr unsigned int max_degree = 4;
  } // namespace

  struct MembraneDistance::Tree
  {
    explicit Tree(const std::vector<Point<3>> &samples)
      : rtree(pack_rtree_of_indices(samples))
    {}

    decltype(pack_rtree_of_indices(
      std::declval<const std::vector<Point<3>> &>())) rtree;
  };

  MembraneDistance::~MembraneDistance() = default;

  MembraneDistance::MembraneDistance(
    const std::vector<const Triangulation<2, 3> *> &membranes,
    const MappingQ<2, 3>                           &mapping,
    const std::optional<double>                    &period)
    : period(period)
  {
    const unsigned int degree = mapping.get_degree();
    AssertThrow(degree >= 1 && degree <= max_degree,
                ExcMessage("MembraneDistance takes membrane mappings of "
                           "degree 1 to 4"));
    const QGaussLobatto<1> lobatto(degree + 1);
    for (const auto &p : lobatto.get_points())
      nodes_1d.push_back(p[0]);
    std::sort(nodes_1d.begin(), nodes_1d.end());
    std::vector<Point<1>> support;
    for (const double t : nodes_1d)
      support.emplace_back(t);
    basis = Polynomials::generate_complete_Lagrange_basis(support);

    // The patch nodes of each cell, in one evaluation of its mapping (which
    // places its support points on the manifold once).
    const unsigned int    n_nodes = degree + 1;
    std::vector<Point<2>> unit_nodes;
    for (unsigned int j = 0; j < n_nodes; ++j)
      for (unsigned int i = 0; i < n_nodes; ++i)
        unit_nodes.emplace_back(nodes_1d[i], nodes_1d[j]);
    const FE_Q<2, 3> fe(1);
    FEValues<2, 3>   node_values(mapping,
                               fe,
                               Quadrature<2>(unit_nodes),
                               update_quadrature_points);
    const QGauss<2>  volume_quadrature(degree + 2);
    for (unsigned int m = 0; m < membranes.size(); ++m)
      {
        const unsigned int first  = patches.size();
        double             volume = 0.;
        for (const auto &cell : membranes[m]->active_cell_iterators())
          {
            Patch patch{m, cell, {}, 1.};
            node_values.reinit(cell);
            patch.nodes = node_values.get_quadrature_points();
            // The enclosed volume, (1/3) ∫ F · (∂₀F × ∂₁F) dξ, tells
            // which side the tangents' normal points to.
            for (unsigned int q = 0; q < volume_quadrature.size(); ++q)
              {
                Point<3>     F;
                Tensor<1, 3> dF0, dF1;
                evaluate(patch, volume_quadrature.point(q), F, dF0, dF1);
                volume += F * cross_product_3d(dF0, dF1) *
                          volume_quadrature.weight(q) / 3.;
              }
            patches.push_back(std::move(patch));
          }
        for (unsigned int k = first; k < patches.size(); ++k)
          patches[k].orientation = volume < 0. ? -1. : 1.;
      }

    const unsigned int n_s = n_samples_1d(degree);
    for (unsigned int k = 0; k < patches.size(); ++k)
      for (unsigned int j = 0; j < n_s; ++j)
        for (unsigned int i = 0; i < n_s; ++i)
          {
            const Point<2> xi(i / (n_s - 1.), j / (n_s - 1.));
            Point<3>       F;
            Tensor<1, 3>   dF0, dF1;
            evaluate(patches[k], xi, F, dF0, dF1);
            samples.push_back(F);
            sample_patch.push_back(k);
            sample_xi.push_back(xi);
          }
    tree = std::make_unique<Tree>(samples);
  }

  void
  MembraneDistance::evaluate(const Patch    &patch,
                             const Point<2> &xi,
                             Point<3>       &F,
                             Tensor<1, 3>   &dF0,
                             Tensor<1, 3>   &dF1) const
  {
    const unsigned int                                n = basis.size();
    std::array<std::array<double, 2>, max_degree + 1> v0, v1;
    for (unsigned int i = 0; i < n; ++i)
      {
        basis[i].value(xi[0], 1, v0[i].data());
        basis[i].value(xi[1], 1, v1[i].data());
      }
    F   = Point<3>();
    dF0 = Tensor<1, 3>();
    dF1 = Tensor<1, 3>();
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        {
          const Tensor<1, 3> &node = patch.nodes[j * n + i];
          F += v0[i][0] * v1[j][0] * node;
          dF0 += v0[i][1] * v1[j][0] * node;
          dF1 += v0[i][0] * v1[j][1] * node;
        }
  }

  MembraneDistance::ClosestPoint
  MembraneDistance::project(const Patch    &patch,
                            const Point<3> &x,
                            Point<2>        xi) const
  {
    // Gauss-Newton on |F(ξ) - x|², ξ kept in the unit square: near the
    // surface, where the level set matters, it converges in a few steps.
    Point<3>     F;
    Tensor<1, 3> dF0, dF1;
    for (unsigned int iteration = 0; iteration < 30; ++iteration)
      {
        evaluate(patch, xi, F, dF0, dF1);
        const Tensor<1, 3> r   = F - x;
        const double       a00 = dF0 * dF0, a01 = dF0 * dF1, a11 = dF1 * dF1;
        const double       g0 = dF0 * r, g1 = dF1 * r;
        const double       det = a00 * a11 - a01 * a01;
        if (!(det > 0.))
          break;
        const Point<2> previous = xi;
        xi[0] -= (a11 * g0 - a01 * g1) / det;
        xi[1] -= (a00 * g1 - a01 * g0) / det;
        for (unsigned int d = 0; d < 2; ++d)
          xi[d] = std::clamp(xi[d], 0., 1.);
        if (previous.distance_square(xi) < 1e-24)
          break;
      }
    evaluate(patch, xi, F, dF0, dF1);

    ClosestPoint result;
    result.membrane  = patch.membrane;
    result.cell      = patch.cell;
    result.reference = xi;
    result.point     = F;
    result.normal    = cross_product_3d(dF0, dF1);
    result.normal *= patch.orientation / result.normal.norm();
    const double distance = x.distance(F);
    result.signed_distance =
      (x - F) * result.normal < 0. ? -distance : distance;
    return result;
  }

  double
  MembraneDistance::winding_number(const unsigned int membrane,
                                   const Point<3>    &x) const
  {
    // The solid angle that the membrane's surface, as the flat triangles
    // between the nodes of its patches, subtends at x over 4π (Van Oosterom
    // & Strackee 1983, IEEE TBME 30:125): 1 inside, 0 outside, and robust
    // to folds the closest point cannot see past.
    const unsigned int n     = nodes_1d.size();
    double             angle = 0.;
    for (const Patch &patch : patches)
      if (patch.membrane == membrane)
        for (unsigned int j = 0; j + 1 < n; ++j)
          for (unsigned int i = 0; i + 1 < n; ++i)
            {
              const Tensor<1, 3> a = patch.nodes[j * n + i] - x;
              const Tensor<1, 3> b = patch.nodes[j * n + i + 1] - x;
              const Tensor<1, 3> c = patch.nodes[(j + 1) * n + i + 1] - x;
              const Tensor<1, 3> d = patch.nodes[(j + 1) * n + i] - x;
              angle += patch.orientation *
                       (solid_angle(a, b, c) + solid_angle(a, c, d));
            }
    return angle / (4. * numbers::PI);
  }

  std::size_t
  MembraneDistance::PointHash::operator()(const Point<3> &x) const
  {
    std::size_t seed = 0;
    for (unsigned int d = 0; d < 3; ++d)
      boost::hash_combine(seed, std::hash<double>()(x[d]));
    return seed;
  }

  void
  MembraneDistance::try_patches_near(const Point<3>            &around,
                                     const Point<3>            &x,
                                     std::vector<unsigned int> &tried,
                                     Candidate                 &best) const
  {
    constexpr double         tie = 1e-8; // [µm], far below any mesh size
    std::vector<std::size_t> nearest;
    tree->rtree.query(boost::geometry::index::nearest(around, n_candidates),
                      std::back_inserter(nearest));
    for (const std::size_t k : nearest)
      {
        if (std::find(tried.begin(), tried.end(), sample_patch[k]) !=
            tried.end())
          continue;
        tried.push_back(sample_patch[k]);
        Candidate candidate;
        candidate.point = project(patches[sample_patch[k]], x, sample_xi[k]);
        candidate.x     = x;
        const double distance = std::abs(candidate.point.signed_distance);
        candidate.alignment =
          distance > 0. ?
            std::abs((x - candidate.point.point) * candidate.point.normal) /
              distance :
            1.;
        const double best_distance = std::abs(best.point.signed_distance);
        if (distance < best_distance - tie ||
            (distance <= best_distance + tie &&
             candidate.alignment > best.alignment))
          best = candidate;
      }
  }

  MembraneDistance::ClosestPoint
  MembraneDistance::closest_point(const Point<3> &x) const
  {
    const auto known = answers.find(x);
    if (known != answers.end())
      return known->second;

    std::vector<Point<3>> images{x};
    if (period)
      for (const double shift : {-*period, *period})
        images.push_back(x + Tensor<1, 3>({shift, 0., 0.}));

    Candidate best;
    best.point.signed_distance = std::numeric_limits<double>::infinity();
    std::vector<std::vector<unsigned int>> tried(images.size());
    for (unsigned int i = 0; i < images.size(); ++i)
      try_patches_near(images[i], images[i], tried[i], best);

    // The side of x: from the normal at the closest point F, which is exact
    // where F lies inside a patch (x - F is then along the normal). Where F
    // lies on an edge or a corner that patches share, each of them finds it
    // with its own normal, and x - F lies in the cone of those normals: on a
    // sharp fold (a parachute's rim at high capillary number, seen from
    // afar) one of them can put x on the wrong side. So every patch around
    // such an F is tried, and of equally close answers the one whose normal
    // is most nearly along x - F gives the side (right at any edge: the two
    // normals' dot products with x - F sum to a non-negative number). Where
    // even that normal is more than 25° off x - F (the corner of a fold,
    // where several patches meet at sharp angles: a parachute's rim at
    // Ca ~ 0.5-1), the winding number decides. That is a few percent of the
    // queries at such a rim, and almost none on a smooth membrane.
    const Point<2> &xi = best.point.reference;
    if (std::min({xi[0], xi[1], 1. - xi[0], 1. - xi[1]}) == 0.)
      {
        const unsigned int i =
          std::find(images.begin(), images.end(), best.x) - images.begin();
        try_patches_near(best.point.point, best.x, tried[i], best);
      }
    if (best.alignment < 0.9)
      best.point.signed_distance =
        (winding_number(best.point.membrane, best.x) > 0.5 ? -1. : 1.) *
        std::abs(best.point.signed_distance);
    answers.emplace(x, best.point);
    return best.point;
  }
} // namespace rbc_ifem

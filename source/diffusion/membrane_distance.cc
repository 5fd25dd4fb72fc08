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

    /// Two closest points closer than this are a tie, which the better
    /// aligned one wins [µm]; far below any mesh size.
    constexpr double tie = 1e-8;

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

    /// Below this alignment of x - F with the normal at a closest point F
    /// inside a patch (Gauss-Newton short of a true minimum) the winding
    /// number gives the side.
    constexpr double min_alignment = 0.9;

    /// Whether a reference coordinate lies on the unit square's edge.
    bool
    on_edge(const double t)
    {
      return t == 0. || t == 1.;
    }
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
        first_patch.push_back(first);
        first_vertex.push_back(vertex_patches.size());
        vertex_patches.resize(vertex_patches.size() +
                              membranes[m]->n_vertices());
        for (const auto &cell : membranes[m]->active_cell_iterators())
          {
            for (const unsigned int v : cell->vertex_indices())
              vertex_patches[first_vertex[m] + cell->vertex_index(v)].push_back(
                patches.size());
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
    find_sample_box(n_s * n_s);
  }

  void
  MembraneDistance::find_sample_box(const unsigned int samples_per_patch)
  {
    if (samples.empty())
      return;
    sample_box = {samples.front(), samples.front()};
    for (std::size_t first = 0; first < samples.size();
         first += samples_per_patch)
      {
        Point<3> lower = samples[first], upper = samples[first];
        for (std::size_t k = first; k < first + samples_per_patch; ++k)
          for (unsigned int d = 0; d < 3; ++d)
            {
              lower[d] = std::min(lower[d], samples[k][d]);
              upper[d] = std::max(upper[d], samples[k][d]);
            }
        sample_margin = std::max(sample_margin, lower.distance(upper));
        for (unsigned int d = 0; d < 3; ++d)
          {
            sample_box.first[d]  = std::min(sample_box.first[d], lower[d]);
            sample_box.second[d] = std::max(sample_box.second[d], upper[d]);
          }
      }
  }

  double
  MembraneDistance::distance_bound(const Point<3> &x) const
  {
    Tensor<1, 3> outside;
    for (unsigned int d = 0; d < 3; ++d)
      outside[d] =
        std::max({sample_box.first[d] - x[d], x[d] - sample_box.second[d], 0.});
    return outside.norm() - sample_margin;
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
    // Clamped to the square it need not descend: on a patch whose corner
    // is sharp (12° at the rim of a cell squeezed through a 6 µm
    // capillary) it can leave a start at that corner, the closest point of
    // a node far behind the rim, for a farther point of an edge. So the
    // closest ξ it visits is the answer, never farther than the start.
    Point<3>     F;
    Tensor<1, 3> dF0, dF1;
    Point<2>     closest_xi       = xi;
    double       closest_distance = std::numeric_limits<double>::infinity();
    for (unsigned int iteration = 0; iteration < 30; ++iteration)
      {
        evaluate(patch, xi, F, dF0, dF1);
        const Tensor<1, 3> r = F - x;
        if (r.norm() < closest_distance)
          {
            closest_distance = r.norm();
            closest_xi       = xi;
          }
        const double a00 = dF0 * dF0, a01 = dF0 * dF1, a11 = dF1 * dF1;
        const double g0 = dF0 * r, g1 = dF1 * r;
        const double det = a00 * a11 - a01 * a01;
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
    if (x.distance(F) > closest_distance)
      {
        xi = closest_xi;
        evaluate(patch, xi, F, dF0, dF1);
      }

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

  double
  MembraneDistance::side(const Candidate &best) const
  {
    const Point<2> &xi = best.point.reference;
    if (!on_edge(xi[0]) && !on_edge(xi[1]))
      {
        if (best.alignment >= min_alignment)
          return best.point.signed_distance < 0. ? -1. : 1.;
      }
    else if (bool outside; patches_around_agree(best, outside))
      return outside ? 1. : -1.;
    return winding_number(best.point.membrane, best.x) > 0.5 ? -1. : 1.;
  }

  bool
  MembraneDistance::patches_around_agree(const Candidate &best,
                                         bool            &outside) const
  {
    const Patch       &patch     = patches[best.patch];
    const Point<2>    &xi        = best.point.reference;
    const Tensor<1, 3> r         = best.x - best.point.point;
    unsigned int       n_outside = 0, n_inside = 0;
    const auto         count = [&](const Tensor<1, 3> &normal) {
      (r * normal > 0. ? n_outside : n_inside) += 1;
    };
    if (on_edge(xi[0]) && on_edge(xi[1]))
      {
        const unsigned int corner = (xi[0] == 1.) + 2 * (xi[1] == 1.);
        const unsigned int vertex = patch.cell->vertex_index(corner);
        for (const unsigned int k :
             vertex_patches[first_vertex[patch.membrane] + vertex])
          for (const unsigned int c : patches[k].cell->vertex_indices())
            if (patches[k].cell->vertex_index(c) == vertex)
              count(
                normal_at(patches[k], GeometryInfo<2>::unit_cell_vertex(c)));
      }
    else if (const unsigned int face =
               on_edge(xi[0]) ? (xi[0] == 0. ? 0 : 1) : (xi[1] == 0. ? 2 : 3);
             patch.cell->at_boundary(face))
      count(best.point.normal); // the edge of an open surface
    else
      {
        const auto         neighbor = patch.cell->neighbor(face);
        const unsigned int back     = patch.cell->neighbor_of_neighbor(face);
        // F lies on the edge the two share: projected from the middle of
        // that edge on the neighbour, it is found there.
        const Point<2> start(back < 2 ? back : 0.5, back < 2 ? 0.5 : back - 2);
        count(best.point.normal);
        count(project(patches[first_patch[patch.membrane] +
                              neighbor->active_cell_index()],
                      best.point.point,
                      start)
                .normal);
      }
    outside = n_outside > 0;
    return n_outside == 0 || n_inside == 0;
  }

  Tensor<1, 3>
  MembraneDistance::normal_at(const Patch &patch, const Point<2> &xi) const
  {
    Point<3>     F;
    Tensor<1, 3> dF0, dF1;
    evaluate(patch, xi, F, dF0, dF1);
    const Tensor<1, 3> normal = cross_product_3d(dF0, dF1);
    return patch.orientation / normal.norm() * normal;
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
        candidate.patch = sample_patch[k];
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

  std::vector<Point<3>>
  MembraneDistance::images_of(const Point<3> &x) const
  {
    std::vector<Point<3>> images{x};
    if (period)
      for (const double shift : {-*period, *period})
        images.push_back(x + Tensor<1, 3>({shift, 0., 0.}));
    return images;
  }

  double
  MembraneDistance::nearest_sample_distance(const Point<3> &x) const
  {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Point<3> &image : images_of(x))
      {
        if (distance_bound(image) >= nearest)
          continue;
        std::vector<std::size_t> found;
        tree->rtree.query(boost::geometry::index::nearest(image, 1),
                          std::back_inserter(found));
        for (const std::size_t k : found)
          nearest = std::min(nearest, image.distance(samples[k]));
      }
    return nearest;
  }

  MembraneDistance::ClosestPoint
  MembraneDistance::closest_point(const Point<3> &x) const
  {
    const auto known = answers.find(x);
    if (known != answers.end())
      return known->second;

    const std::vector<Point<3>> images = images_of(x);
    Candidate                   best;
    best.point.signed_distance = std::numeric_limits<double>::infinity();
    std::vector<std::vector<unsigned int>> tried(images.size());
    for (unsigned int i = 0; i < images.size(); ++i)
      // An image that cannot come within the tie of the best so far is
      // not tried: the answer is the same, and in a periodic segment most
      // points' images are a period away from every membrane.
      if (distance_bound(images[i]) <=
          std::abs(best.point.signed_distance) + tie)
        try_patches_near(images[i], images[i], tried[i], best);

    // The side of x: from the normal at the closest point F, which is exact
    // where F lies inside a patch (x - F is then along the normal). Where F
    // lies on an edge or a corner that patches share, x - F lies in the
    // cone of their normals, and on a sharp fold (a parachute's rim at high
    // capillary number) the normal of one of them, even the one most nearly
    // along x - F, can put x on the wrong side: at the rim of a cell
    // squeezed through a 6 µm capillary, where four patches meet at 69° in
    // all and two fold back on each other, level set nodes in the vessel
    // wall landed on the cell's inside that way, and so did nodes 6 µm
    // behind it, whose closest point then was on an edge. So every patch
    // around such an F is tried for a closer point, and where the patches
    // around F disagree the winding number gives the side (side()).
    const Point<2> &xi = best.point.reference;
    if (on_edge(xi[0]) || on_edge(xi[1]))
      {
        const unsigned int i =
          std::find(images.begin(), images.end(), best.x) - images.begin();
        try_patches_near(best.point.point, best.x, tried[i], best);
      }
    best.point.signed_distance =
      side(best) * std::abs(best.point.signed_distance);
    answers.emplace(x, best.point);
    return best.point;
  }
} // namespace rbc_ifem

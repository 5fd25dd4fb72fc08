#ifndef rbc_ifem_diffusion_membrane_distance_h
#define rbc_ifem_diffusion_membrane_distance_h

#include <deal.II/base/point.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The signed distance from a point to a set of closed membranes, and the
   * closest point on them: what the cut-cell uptake solve needs to build a
   * level set of the plasma around the cells (CutCellDiffusion) and to hand
   * the flux it computes back to the membranes.
   *
   * Each membrane cell is curved by @p mapping, a MappingQ of degree p: its
   * map is the tensor-product Lagrange interpolant at the (p+1)² Gauss-Lobatto
   * points, which this class samples once and then evaluates itself. The
   * closest point is found by Gauss-Newton in the reference coordinates of
   * the cells of the nearest sampled points (an R-tree of all samples), so
   * a query costs a few small 2×2 solves, not a search of the surface.
   *
   * The distance is positive outside every cell and negative inside one; the
   * outward side of each membrane is found from the sign of its enclosed
   * volume, so either orientation of the membrane mesh works.
   */
  class MembraneDistance
  {
  public:
    /// What a query returns.
    struct ClosestPoint
    {
      double       signed_distance = 0.; ///< [µm], < 0 inside a cell
      unsigned int membrane        = 0;  ///< index into the membranes
      /// The membrane cell that holds the closest point.
      typename Triangulation<2, 3>::active_cell_iterator cell;
      Point<2>                                           reference;
      Point<3>                                           point;
      Tensor<1, 3> normal; ///< unit outward normal there
    };

    /**
     * Sample @p membranes, curved by @p mapping (a MappingQ). With a
     * @p period along x the segment is periodic: the distance is to the
     * nearest periodic image of each membrane.
     */
    MembraneDistance(const std::vector<const Triangulation<2, 3> *> &membranes,
                     const MappingQ<2, 3>                           &mapping,
                     const std::optional<double> &period = std::nullopt);

    ~MembraneDistance();

    MembraneDistance(const MembraneDistance &) = delete;
    MembraneDistance &
    operator=(const MembraneDistance &) = delete;

    /**
     * The closest membrane point to @p x and its signed distance. Each
     * answer is remembered, so that a point asked again (a level set node
     * of a mesh refined around the membranes and built again) costs a
     * lookup.
     */
    ClosestPoint
    closest_point(const Point<3> &x) const;

    /**
     * The distance from @p x to the nearest of the points the membranes
     * are sampled at (the nearest periodic image's, in a periodic
     * segment): at least the distance to the membranes and at most the
     * sample spacing more, for a hundredth of a closest_point()'s cost. It
     * has no sign: where only the distance of a point known to lie in the
     * plasma matters, not where it is.
     */
    double
    nearest_sample_distance(const Point<3> &x) const;

  private:
    /// One membrane cell as a polynomial patch of degree p.
    struct Patch
    {
      unsigned int                                       membrane;
      typename Triangulation<2, 3>::active_cell_iterator cell;
      std::vector<Point<3>> nodes; ///< lexicographic, (p+1)²
      double orientation;          ///< +1 or -1: ∂₀F × ∂₁F outward?
    };

    /// A patch's answer to a query from the point (or periodic image) x.
    struct Candidate
    {
      ClosestPoint point;
      Point<3>     x;
      /// |(x - F) · n| / |x - F|: 1 where x - F is along the normal.
      double       alignment = 0.;
      unsigned int patch     = 0; ///< index into patches
    };

    /**
     * Project @p x on the patches of the samples nearest to @p around that
     * are not in @p tried yet (and add them to it), and keep in @p best the
     * closest answer; of answers equally close (on an edge or a corner that
     * patches share), the one best aligned with its normal.
     */
    void
    try_patches_near(const Point<3>            &around,
                     const Point<3>            &x,
                     std::vector<unsigned int> &tried,
                     Candidate                 &best) const;


    /// The winding number of @p membrane around @p x: 1 inside, 0 outside.
    double
    winding_number(unsigned int membrane, const Point<3> &x) const;

    /**
     * The side of @p best.x, the point whose closest point on the
     * membranes @p best found: -1 inside its membrane, +1 outside. From the
     * normal at the closest point F where F lies inside a patch and x - F
     * is along its normal; where F lies on an edge or a corner, from the
     * normals there of all the patches around F if they agree; otherwise
     * (x - F more than 25° off the normal inside a patch, or the patches
     * around F disagree: a sharp fold) from the winding number.
     */
    double
    side(const Candidate &best) const;

    /**
     * Whether the normals at F of all the patches around the edge or
     * corner F of @p best put @p best.x on the same side; that side in
     * @p outside.
     */
    bool
    patches_around_agree(const Candidate &best, bool &outside) const;

    /// The outward unit normal of @p patch at @p xi.
    Tensor<1, 3>
    normal_at(const Patch &patch, const Point<2> &xi) const;

    /// F(ξ) and its two tangents on @p patch.
    void
    evaluate(const Patch    &patch,
             const Point<2> &xi,
             Point<3>       &F,
             Tensor<1, 3>   &dF0,
             Tensor<1, 3>   &dF1) const;

    /// The closest point to @p x on @p patch, from the start @p xi.
    ClosestPoint
    project(const Patch &patch, const Point<3> &x, Point<2> xi) const;

    std::vector<Polynomials::Polynomial<double>>
                        basis; ///< 1-D Lagrange, degree p
    std::vector<double> nodes_1d;
    std::vector<Patch>  patches;
    /// The patches of membrane m are first_patch[m] + the active cell
    /// index; its vertex v is first_vertex[m] + v in vertex_patches, the
    /// patches around each vertex.
    std::vector<unsigned int>              first_patch;
    std::vector<unsigned int>              first_vertex;
    std::vector<std::vector<unsigned int>> vertex_patches;
    /// Sample k: patch sample_patch[k] at reference point sample_xi[k].
    std::vector<Point<3>>     samples;
    std::vector<unsigned int> sample_patch;
    std::vector<Point<2>>     sample_xi;
    /// An R-tree of indices into samples (which it refers to: the class
    /// cannot move); declared in the .cc, so that the headers that include
    /// this one do not parse Boost.Geometry.
    struct Tree;
    std::unique_ptr<Tree> tree;
    std::optional<double> period;
    /// The box around every sample, and how far a point of a patch can be
    /// from its samples at most (the longest diagonal of a patch's box of
    /// samples): a lower bound on the distance from any point to the
    /// membranes, which rules out periodic images far from them.
    std::pair<Point<3>, Point<3>> sample_box;
    double                        sample_margin = 0.;

    /// @p x, and in a periodic segment its images a period before and
    /// after it.
    std::vector<Point<3>>
    images_of(const Point<3> &x) const;

    /// A lower bound on the distance from @p x to every membrane.
    double
    distance_bound(const Point<3> &x) const;

    /// Set sample_box and sample_margin from the samples, which come in
    /// blocks of @p samples_per_patch per patch.
    void
    find_sample_box(const unsigned int samples_per_patch);

    /// The bits of a point's coordinates: exact equality, hashed.
    struct PointHash
    {
      std::size_t
      operator()(const Point<3> &x) const;
    };
    mutable std::unordered_map<Point<3>, ClosestPoint, PointHash> answers;
  };
} // namespace rbc_ifem

#endif

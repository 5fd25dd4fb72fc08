#ifndef rbc_ifem_membrane_deformed_surface_mapping_h
#define rbc_ifem_membrane_deformed_surface_mapping_h

#include <deal.II/base/point.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <map>
#include <memory>
#include <vector>

namespace rbc_ifem
{
  using namespace dealii;

  class Membrane;

  /**
   * The curved surfaces of deformed membranes, for the CO uptake solve: the
   * reference surface as its manifolds curve it (the Evans-Fung shape,
   * exactly to the mapping's degree) plus the membrane's displacement
   * x - X, interpolated by the membrane's own finite element.
   *
   * The membrane mechanics sees flat Q1 cells between the nodes; a diffusion
   * solve on those facets sees the facets too (0.35% in the default cell's
   * DM at Surface refinements 4), and their edges slow its mesh convergence.
   * This mapping passes through the same nodes, is the reference shape
   * exactly when x = X, and is smooth where the displacement is.
   *
   * It is a MappingQ of degree 2 whose support points are computed once, in
   * the constructor, for every cell of every surface it is given (the
   * surfaces of Membrane::build_surface: copies of the reference meshes with
   * the current vertices); it maps the cells of those surfaces only.
   */
  class DeformedSurfaceMapping : public MappingQ<2, 3>
  {
  public:
    /**
     * The mapping of @p surfaces[c], the current surface of
     * @p membranes[c] at positions @p positions[c], for every c. The
     * reference meshes of the membranes must carry their manifolds.
     */
    DeformedSurfaceMapping(
      const std::vector<const Triangulation<2, 3> *> &surfaces,
      const std::vector<const Membrane *>            &membranes,
      const std::vector<Vector<double>>              &positions);

    /**
     * The same with surface c's membrane given by @p membrane_of(c), asked
     * for one c at a time: each need live only while its surface's support
     * points are taken, so that a caller can make the membranes it does not
     * keep one by one.
     */
    DeformedSurfaceMapping(
      const std::vector<const Triangulation<2, 3> *> &surfaces,
      const std::function<std::shared_ptr<const Membrane>(unsigned int)>
                                        &membrane_of,
      const std::vector<Vector<double>> &positions);

    std::unique_ptr<Mapping<2, 3>>
    clone() const override;

  protected:
    std::vector<Point<3>>
    compute_mapping_support_points(
      const typename Triangulation<2, 3>::cell_iterator &cell) const override;

  private:
    /// For each surface, the support points of each active cell.
    using SupportPoints =
      std::map<const Triangulation<2, 3> *, std::vector<std::vector<Point<3>>>>;
    std::shared_ptr<const SupportPoints> support_points;
  };
} // namespace rbc_ifem

#endif

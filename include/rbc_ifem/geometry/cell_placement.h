#ifndef rbc_ifem_geometry_cell_placement_h
#define rbc_ifem_geometry_cell_placement_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * Where one red cell sits: the centre of its reference shape and the
   * direction of its symmetry axis. The cell's local frame has its axis as
   * the third unit vector; rotation() maps local to global coordinates.
   */
  struct CellPlacement
  {
    Point<3>     center;
    Tensor<1, 3> axis{{1., 0., 0.}};

    /**
     * The proper rotation Q = [u v axis] whose third column is the unit axis;
     * u is built from the coordinate direction least aligned with the axis,
     * so Q depends continuously on the axis away from those switch points.
     */
    Tensor<2, 3>
    rotation() const
    {
      const Tensor<1, 3> a     = axis / axis.norm();
      unsigned int       least = 0;
      for (unsigned int d = 1; d < 3; ++d)
        if (std::abs(a[d]) < std::abs(a[least]))
          least = d;
      Tensor<1, 3> e;
      e[least]       = 1.;
      Tensor<1, 3> u = cross_product_3d(e, a);
      u /= u.norm();
      const Tensor<1, 3> v = cross_product_3d(a, u);
      Tensor<2, 3>       q;
      for (unsigned int i = 0; i < 3; ++i)
        {
          q[i][0] = u[i];
          q[i][1] = v[i];
          q[i][2] = a[i];
        }
      return q;
    }
  };
} // namespace rbc_ifem

#endif

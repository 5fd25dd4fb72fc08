#ifndef rbc_ifem_geometry_shear_box_mesh_h
#define rbc_ifem_geometry_shear_box_mesh_h

#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The box of Experiment = shear, centred on the origin: @p box = (length,
   * height, width) along x, y, z, cut into cubes of edge @p cell_size and
   * refined @p n_global_refinements times. Boundary ids as in the capillary
   * (FluidBoundary): the ends x = ±L/2 are the inlet (1) and the outlet (2),
   * open; the faces y = ±H/2 and z = ±W/2 are the wall (0), where the shear
   * is imposed.
   */
  void
  create_shear_box_mesh(Triangulation<3>   &triangulation,
                        const Tensor<1, 3> &box,
                        const double        cell_size,
                        const unsigned int  n_global_refinements);
} // namespace rbc_ifem

#endif

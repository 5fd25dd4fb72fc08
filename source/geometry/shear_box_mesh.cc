#include <rbc_ifem/geometry/capillary_mesh.h>
#include <rbc_ifem/geometry/shear_box_mesh.h>

#include <deal.II/grid/grid_generator.h>

#include <cmath>
#include <vector>

namespace rbc_ifem
{
  void
  create_shear_box_mesh(Triangulation<3>   &triangulation,
                        const Tensor<1, 3> &box,
                        const double        cell_size,
                        const unsigned int  n_global_refinements)
  {
    std::vector<unsigned int> repetitions(3);
    for (unsigned int d = 0; d < 3; ++d)
      repetitions[d] =
        static_cast<unsigned int>(std::lround(box[d] / cell_size));
    const Point<3> corner(box / 2.);
    GridGenerator::subdivided_hyper_rectangle(
      triangulation, repetitions, -corner, corner, true);
    // colorize numbers the faces 2d (low) and 2d + 1 (high) along axis d.
    for (const auto &face : triangulation.active_face_iterators())
      if (face->at_boundary())
        {
          const types::boundary_id colour = face->boundary_id();
          face->set_boundary_id(colour == 0 ? FluidBoundary::inlet :
                                colour == 1 ? FluidBoundary::outlet :
                                              FluidBoundary::wall);
        }
    triangulation.refine_global(n_global_refinements);
  }
} // namespace rbc_ifem

// The signed distance of MembraneDistance at a sharp fold of a membrane, where
// the closest point lies on an edge that two patches share: the case of a
// parachute's rim at high capillary number, which once put level set nodes
// at the vessel wall on the wrong side (a spurious membrane in the wall).
//
// The membrane is the surface of a wedge that widens towards its end: the
// unit cube mapped by (x, y, z) -> (x, 1/2 + (y - 1/2)(1 + 3x), z). Its top
// face y = 1 + 3x/2 and its end face x = 1 meet at the edge E = (1, 5/2, z)
// under 146.3° between their outward normals (a 33.7° wedge). A point
// E + t u, u in the plane z = const at an angle φ from the end face's
// normal (1, 0, 0) towards the top face's, lies at the distance t outside
// for every φ from 0 to 146.3°; from the top face's normal alone φ < 56.3°
// would be inside. A point on the wedge's bisector inside, E - s w, lies at
// s sin(16.85°) inside.

#include <rbc_ifem/diffusion/membrane_distance.h>

#include "check.h"

#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <cmath>

using namespace rbc_ifem;

int
main()
{
  Checker check;

  Triangulation<3> wedge;
  GridGenerator::subdivided_hyper_cube(wedge, 4);
  GridTools::transform(
    [](const Point<3> &p) {
      return Point<3>(p[0], 0.5 + (p[1] - 0.5) * (1. + 3. * p[0]), p[2]);
    },
    wedge);
  Triangulation<2, 3> membrane;
  GridGenerator::extract_boundary_mesh(wedge, membrane);
  const MappingQ<2, 3>   mapping(2);
  const MembraneDistance distance({&membrane}, mapping);

  const double top_angle     = std::atan2(1., -1.5); // of (-3/2, 1): 146.3°
  unsigned int wrong_side    = 0;
  double       largest_error = 0.;
  for (const double z : {0.3, 0.5, 0.7})
    {
      const Point<3> edge(1., 2.5, z);
      for (const double fraction : {0.02, 0.1, 0.3, 0.5, 0.6, 0.9, 0.98})
        for (const double t : {0.05, 0.5, 2.})
          {
            const double   phi = fraction * top_angle;
            const Point<3> x =
              edge + t * Tensor<1, 3>({std::cos(phi), std::sin(phi), 0.});
            const double d = distance.closest_point(x).signed_distance;
            wrong_side += (d <= 0.);
            largest_error = std::max(largest_error, std::abs(std::abs(d) - t));
          }
      // Inside, on the bisector of the wedge.
      const double half     = (numbers::PI - top_angle) / 2.;
      const double bisector = top_angle / 2. + numbers::PI; // inward
      for (const double s : {0.05, 0.2})
        {
          const Point<3> x =
            edge +
            s * Tensor<1, 3>({std::cos(bisector), std::sin(bisector), 0.});
          const double d = distance.closest_point(x).signed_distance;
          wrong_side += (d >= 0.);
          largest_error =
            std::max(largest_error, std::abs(std::abs(d) - s * std::sin(half)));
        }
    }
  check.near("points on the wrong side of the fold (of 69)", wrong_side, 0, 0);
  check.at_most("largest error of |distance| [µm]", largest_error, 1e-8);
  return check.exit_code();
}

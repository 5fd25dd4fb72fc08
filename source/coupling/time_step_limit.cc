#include <rbc_ifem/coupling/time_step_limit.h>

#include <deal.II/base/numbers.h>

#include <algorithm>

namespace rbc_ifem
{
  CouplingTimeStepLimit::CouplingTimeStepLimit(const double viscosity,
                                               const MembraneParameters &m,
                                               const double point_spacing,
                                               const double mesh_size)
  {
    const double q =
      dealii::numbers::PI / std::max(point_spacing, 0.5 * mesh_size);
    in_plane =
      8. * viscosity / ((m.area_dilation_modulus + m.shear_modulus) * q);
    bending = 8. * viscosity / (m.bending_modulus * q * q * q);
    limit   = std::min(in_plane, bending);
  }
} // namespace rbc_ifem

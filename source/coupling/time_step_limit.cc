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

  void
  CouplingTimeStepLimit::include_contact(const double viscosity,
                                         const double stiffness,
                                         const double diameter)
  {
    if (stiffness <= 0.)
      return;
    contact =
      std::min(contact,
               8. * dealii::numbers::PI * viscosity / (diameter * stiffness));
    limit = std::min(limit, contact);
  }

  void
  CouplingTimeStepLimit::include_advection(const double speed,
                                           const double distance)
  {
    if (speed > 0.)
      advective = distance / speed;
  }
} // namespace rbc_ifem

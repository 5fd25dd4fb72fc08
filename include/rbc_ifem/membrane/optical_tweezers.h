#ifndef rbc_ifem_membrane_optical_tweezers_h
#define rbc_ifem_membrane_optical_tweezers_h

#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/lac/vector.h>

namespace rbc_ifem
{
  using namespace dealii;

  /**
   * The unit pull of the optical-tweezers test (Mills et al. 2004) on a
   * cell whose diameter lies along x: two beads, each holding
   * @p attached_fraction of the membrane area at one end of the diameter,
   * pull with total forces ±1 pN, spread over the nodes of their patch in
   * proportion to the nodes' areas (+a_i/A_patch on the x DoFs of the right
   * patch, -a_i/A_patch on the left). Scale it by the bead force F for the
   * external forces of find_equilibrium().
   */
  Vector<double>
  bead_forces(const Membrane &membrane, const double attached_fraction);

  /// The extents of the membrane at @p x along x (the axial diameter, the
  /// beads' direction) and along y (the transverse diameter) [µm].
  struct StretchDiameters
  {
    double axial      = 0.;
    double transverse = 0.;
  };

  StretchDiameters
  stretch_diameters(const Membrane &membrane, const Vector<double> &x);
} // namespace rbc_ifem

#endif

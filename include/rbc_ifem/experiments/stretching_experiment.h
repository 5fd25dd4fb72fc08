#ifndef rbc_ifem_stretching_experiment_h
#define rbc_ifem_stretching_experiment_h

#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

namespace rbc_ifem
{
  class Membrane;

  /**
   * Experiment "stretching": the optical-tweezers test. One cell, its disc
   * in the x-y plane, is pulled along x by two beads with equal and
   * opposite total forces ±F, each spread over the nodes of a patch at one
   * end of the diameter in proportion to their area (the patch holds
   * Stretching/Attached area fraction of the membrane). For F = 0 and
   * Number of force steps equal steps up to Maximum force the static
   * equilibrium is found by find_equilibrium() from the previous one;
   * stretch.csv gets force, axial_diameter (x extent), transverse_diameter
   * (y extent), area and volume, and each equilibrium is written as
   * stretch_NNN.vtu (stretch.pvd, with the force as its "time").
   *
   * The membrane problem is small (a few thousand DoFs) and is solved on
   * rank 0; other ranks wait.
   */
  class StretchingExperiment
  {
  public:
    StretchingExperiment(const Parameters &parameters,
                         const MPI_Comm    communicator);

    void
    run(const ParameterHandler &prm);

  private:
    /// The unit pulling force: +a_i/A_patch on the x DoFs of the right
    /// patch, -a_i/A_patch on the left one.
    Vector<double>
    bead_forces(const Membrane &membrane) const;

    const Parameters   parameters;
    const MPI_Comm     communicator;
    ConditionalOStream pcout;
  };
} // namespace rbc_ifem

#endif

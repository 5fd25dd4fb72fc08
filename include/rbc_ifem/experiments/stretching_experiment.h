#ifndef rbc_ifem_experiments_stretching_experiment_h
#define rbc_ifem_experiments_stretching_experiment_h

#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/membrane/membrane.h>

#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <memory>

namespace rbc_ifem
{
  /// The optical-tweezers experiment (subsection "Stretching").
  struct StretchingParameters : public ExperimentParameters
  {
    double       max_force         = 200.; ///< [pN]
    unsigned int n_force_steps     = 8;
    double       attached_fraction = 0.025; ///< of the membrane area, per bead
    double       tolerance         = 1e-3;  ///< nodal force residual [pN]
    unsigned int max_iterations    = 20000;

    void
    add_parameters(ParameterHandler &prm) override;
  };

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
   * stretch_NNN.vtu (stretch.pvd, with the force as its "time"), all once
   * the last equilibrium is found (ParametersFile::after_work: a failed
   * equilibrium leaves nothing behind).
   *
   * The membrane problem is small (a few thousand DoFs) and is solved on
   * rank 0; other ranks wait.
   */
  class StretchingExperiment : public Experiment
  {
  public:
    StretchingExperiment(const ExperimentContext    &context,
                         const StretchingParameters &stretching);

  private:
    /// The membrane (rank 0).
    void
    setup() override;
    /// find_equilibria() on rank 0; every rank throws if it failed.
    void
    execute() override;

    /// The equilibria and their files.
    void
    find_equilibria();

    const StretchingParameters stretching;
    Triangulation<2, 3>        surface;
    std::unique_ptr<Membrane>  membrane;
  };
} // namespace rbc_ifem

#endif

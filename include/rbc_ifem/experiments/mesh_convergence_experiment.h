#ifndef rbc_ifem_experiments_mesh_convergence_experiment_h
#define rbc_ifem_experiments_mesh_convergence_experiment_h

#include <rbc_ifem/experiments/uptake_experiment.h>

#include <memory>

namespace rbc_ifem
{
  /// The mesh-convergence study (subsection "Mesh convergence").
  struct MeshConvergenceParameters : public ExperimentParameters
  {
    unsigned int n_levels = 4;
    /// Refine the membranes with the band (the multiplier needs it: its
    /// membranes must stay coarser than the mesh); false keeps
    /// Cells/Surface refinements on every level.
    bool refine_membranes = true;

    void
    add_parameters(ParameterHandler &prm) override;
  };

  /**
   * Experiment "mesh convergence": DM of the layout of subsection Layout on
   * successively finer meshes, level 0 the mesh of subsection Mesh and
   * Cells/Surface refinements, each further level one more refinement of
   * the diffusion mesh's band and (with Refine membranes) of the
   * membranes. Writes convergence.csv
   * with each level's change from the one before and its difference from
   * the Richardson-extrapolated limit.
   */
  class MeshConvergenceExperiment : public UptakeExperiment
  {
  public:
    MeshConvergenceExperiment(const ExperimentContext         &context,
                              const MeshConvergenceParameters &study);

  private:
    /// The layout, and the membranes of level 0 checked for clearance
    /// (finer levels follow the true surfaces more closely).
    void
    setup() override;
    void
    execute() override;
    /// Cells/Surface refinements of the membranes of @p level.
    unsigned int
    membrane_refinements(const unsigned int level) const;

    const MeshConvergenceParameters    study;
    std::unique_ptr<const PlacedCells> coarsest; ///< the cells of level 0
  };
} // namespace rbc_ifem

#endif

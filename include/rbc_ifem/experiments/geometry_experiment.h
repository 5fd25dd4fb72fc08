#ifndef rbc_ifem_experiments_geometry_experiment_h
#define rbc_ifem_experiments_geometry_experiment_h

#include <rbc_ifem/experiments/experiment.h>
#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_membranes.h>

#include <deal.II/distributed/shared_tria.h>

#include <memory>

namespace rbc_ifem
{
  /**
   * Experiment "geometry": build the cell layout, the membrane meshes and
   * the fluid and diffusion meshes (refined in a band around the cells),
   * check that no cell overlaps another or touches the wall, and write
   * everything out: meshes with their ids, membranes, cells.csv with each
   * cell's centroid, area and volume, the hematocrit in the log.
   *
   * Every check runs before the output directory is touched, so a bad
   * request writes nothing.
   */
  class GeometryExperiment : public Experiment
  {
  public:
    explicit GeometryExperiment(const ExperimentContext &context);

  private:
    /// The layout, the clearance check and the meshes.
    void
    setup() override;
    /// Write the meshes, the membranes and cells.csv.
    void
    execute() override;

    void
    report_membranes();
    void
    create_meshes();

    std::unique_ptr<const CellLayout>    layout;
    std::unique_ptr<const CellMembranes> membranes;

    parallel::shared::Triangulation<3> fluid_mesh;
    parallel::shared::Triangulation<3> diffusion_mesh;
  };
} // namespace rbc_ifem

#endif

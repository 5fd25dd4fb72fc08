#ifndef rbc_ifem_geometry_experiment_h
#define rbc_ifem_geometry_experiment_h

#include <rbc_ifem/geometry/cell_layout.h>
#include <rbc_ifem/geometry/cell_membranes.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>

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
  class GeometryExperiment
  {
  public:
    GeometryExperiment(const Parameters &parameters,
                       const MPI_Comm    communicator);

    /// Build and check everything, then write it (with @p prm as used).
    void
    run(const ParameterHandler &prm);

  private:
    void
    report_membranes() const;
    void
    create_meshes();
    void
    write_output(const ParameterHandler &prm) const;

    const Parameters    parameters;
    const MPI_Comm      communicator;
    ConditionalOStream  pcout;
    mutable TimerOutput timer;

    const CellLayout    layout;
    const CellMembranes membranes;

    parallel::shared::Triangulation<3> fluid_mesh;
    parallel::shared::Triangulation<3> diffusion_mesh;
  };
} // namespace rbc_ifem

#endif

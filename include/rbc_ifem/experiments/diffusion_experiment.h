#ifndef rbc_ifem_diffusion_experiment_h
#define rbc_ifem_diffusion_experiment_h

#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/types.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <functional>
#include <string>
#include <vector>

namespace rbc_ifem
{
  class CODiffusion;

  /// What one diffusion solve of one layout gives.
  struct LayoutUptake
  {
    double                  hematocrit = 0.;
    double                  dm_total   = 0.; ///< [µm³ s⁻¹ Torr⁻¹]
    std::vector<double>     dm_cells;        ///< [µm³ s⁻¹ Torr⁻¹]
    unsigned int            n_nodes    = 0;  ///< vertices of the volume mesh
    unsigned int            n_cells    = 0;  ///< cells of the volume mesh
    types::global_dof_index n_dofs     = 0;  ///< P and λ
    unsigned int            iterations = 0;
    double                  seconds    = 0.; ///< wall time of the whole solve
  };

  /**
   * Solve for the CO uptake of the membranes @p surfaces (curved by
   * @p mapping), on the capillary's diffusion mesh refined
   * @p band_refinements times in the band around their vertices; then call
   * @p write_fields, if given, to write what the caller wants of the solve.
   * The hematocrit of the result is left to the caller.
   */
  LayoutUptake
  solve_uptake(
    const Parameters                               &parameters,
    const std::vector<const Triangulation<2, 3> *> &surfaces,
    const MappingQ<2, 3>                           &mapping,
    const unsigned int                              band_refinements,
    const MPI_Comm                                  communicator,
    TimerOutput                                    &timer,
    const std::function<void(const CODiffusion &)> &write_fields = {});

  /**
   * Build the layout @p layout of the run's cells, their membranes
   * (@p surface_refinements), the diffusion mesh around them (refined
   * @p band_refinements times in the band), and solve for the CO uptake.
   * If @p fields is not empty, also write the P field and the flux map as
   * FIELDS_* and cells.csv to the run's output directory.
   */
  LayoutUptake
  solve_layout(const Parameters       &parameters,
               const LayoutParameters &layout,
               const unsigned int      surface_refinements,
               const unsigned int      band_refinements,
               const MPI_Comm          communicator,
               TimerOutput            &timer,
               const std::string      &fields = "");

  /**
   * The CO uptake experiments, each a steady diffusion solve (CODiffusion)
   * per layout on the capillary's diffusion mesh, refined in a band around
   * the membranes:
   *
   * - "diffusion": the layout of subsection Layout; writes dm.csv (time 0),
   *   cells.csv, the P field and the membrane flux map (VTU + pvd);
   * - "layouts": every kind and number of cells of subsection Layout study,
   *   random layouts over several seeds; writes layouts.csv;
   * - "mesh convergence": the layout of subsection Layout on successively
   *   finer meshes; writes convergence.csv with the difference of each
   *   level from the Richardson-extrapolated limit.
   *
   * Nothing is written before the last solve has succeeded (dm.csv and the
   * fields of "diffusion" after its solve, the tables at the end), so a bad
   * request or a failed solve leaves no file that looks complete.
   */
  class DiffusionExperiment
  {
  public:
    DiffusionExperiment(const Parameters &parameters,
                        const MPI_Comm    communicator);

    void
    run(const ParameterHandler &prm);

  private:
    void
    run_diffusion();
    void
    run_layouts();
    void
    run_mesh_convergence();

    /// The layouts of the study, checked (InputError names the study's entry).
    std::vector<std::vector<LayoutParameters>>
    study_layouts() const;

    /// The progress line of one solve.
    void
    report(const std::string &what, const LayoutUptake &uptake) const;

    const Parameters    parameters;
    const MPI_Comm      communicator;
    ConditionalOStream  pcout;
    mutable TimerOutput timer;
  };
} // namespace rbc_ifem

#endif

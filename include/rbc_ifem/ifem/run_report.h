#ifndef rbc_ifem_ifem_run_report_h
#define rbc_ifem_ifem_run_report_h

#include <rbc_ifem/base/mpi_traffic.h>
#include <rbc_ifem/coupling/cell_population.h>
#include <rbc_ifem/coupling/time_step_limit.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/run_record.h>
#include <rbc_ifem/parameters.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

namespace rbc_ifem
{
  /**
   * What a flowing run tells its user on rank 0's standard output besides
   * its progress lines: at the start, the cells, the dimensionless numbers
   * and the coupling's time step against its stability estimate, with the
   * warnings they call for; at the end, the summary; at both, what each
   * rank holds (load_balance()).
   */
  class RunReport
  {
  public:
    /// The report of the run of @p parameters in @p domain (both must
    /// outlive it).
    RunReport(const Parameters &parameters,
              const FlowDomain &domain,
              const MPI_Comm    communicator);

    /**
     * The start-up lines: @p cells, the fluid mesh size @p mesh_size at
     * them [µm], the Reynolds and capillary numbers, the explicit
     * coupling's estimate @p stable and the time step @p time_step [s]; and
     * the warnings (a time step near the explicit limit, a repulsion range
     * shorter than the point spacing, points farther apart than h/2).
     */
    void
    startup(const CellPopulation        &cells,
            const CouplingTimeStepLimit &stable,
            const double                 mesh_size,
            const double                 time_step) const;

    /**
     * The end-of-run lines: @p n_run steps in @p wall_seconds, DM first and
     * last of @p record (and in mL/(min mmHg)), the cells' deformation
     * index, their volume and area drift and the largest local area change.
     */
    void
    summary(const RunRecord      &record,
            const CellPopulation &cells,
            const unsigned int    n_run,
            const double          wall_seconds) const;

    /**
     * What each rank holds and computes, least to most over the ranks
     * (collective): the red cells it owns (CellOwners) of those it holds
     * and the others in contact reach of them (its ghosts, CellBoxes),
     * @p points_here membrane points in its @p fluid_cells_here fluid
     * cells. The spread is the load balance (doc/scaling.md).
     */
    void
    load_balance(const CellPopulation &cells,
                 const unsigned int    points_here,
                 const unsigned int    fluid_cells_here) const;

    /**
     * What each rank asked of MPI in a run's @p n_run steps, @p during them
     * (MpiTraffic::so_far() after, less before), per step, least to most
     * over the ranks (collective): collective calls, point-to-point
     * messages and their bytes, and the bytes put into the collectives. Whether
     * the communication grows with the cells (doc/scaling.md). With them, how
     * many times in the run a red
     * cell went to another owner, @p handovers (CellOwners::place()).
     */
    void
    communication(const MpiTraffic  &during,
                  const unsigned int n_run,
                  const unsigned int handovers) const;

  private:
    /// The start-up warnings.
    void
    warn(const CellPopulation        &cells,
         const CouplingTimeStepLimit &stable,
         const double                 mesh_size,
         const double                 time_step) const;
    /// The summary's line on DM.
    void
    summarize_dm(const RunRecord &record) const;
    /// The summary's line on the cells' shapes.
    void
    summarize_cells(const CellPopulation &cells) const;

    const Parameters  &parameters;
    const FlowDomain  &domain;
    const MPI_Comm     communicator;
    ConditionalOStream pcout;
  };
} // namespace rbc_ifem

#endif

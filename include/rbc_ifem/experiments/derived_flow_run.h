#ifndef rbc_ifem_experiments_derived_flow_run_h
#define rbc_ifem_experiments_derived_flow_run_h

#include <rbc_ifem/experiments/registry.h>
#include <rbc_ifem/ifem/flow_domain.h>
#include <rbc_ifem/ifem/run_observer.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

namespace rbc_ifem
{
  /**
   * One flowing run of an experiment that runs several (shear, flowing
   * layouts), each derived from the experiment's parameters
   * (RunParameters::derive()) into its own Output directory: the
   * IFEMSimulation of @p run's parameters in @p domain with @p observer,
   * set up (InputError before anything is written), then its
   * parameters.prm, the run (its tables and fields) and its own timing.csv.
   * Its timer summary goes to @p pcout.
   */
  void
  run_derived_flow(const RunParameters &run,
                   const FlowDomain    &domain,
                   RunObserver         &observer,
                   const MPI_Comm       communicator,
                   ConditionalOStream  &pcout);
} // namespace rbc_ifem

#endif

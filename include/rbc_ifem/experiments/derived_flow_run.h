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
   * What a study (shear, flowing layouts) sets of Immersed cells for its run
   * of @p n_steps steps in @p directory, so that the study can be resumed:
   * Resume = true if the study resumes (its @p study parameters say Resume
   * = true) and @p directory holds that run's checkpoint, else false; and a
   * Checkpoint interval of the study's, or of @p n_steps where the study's
   * is 0, so that every run ends with a checkpoint. A resumed study so runs
   * each of its runs on from where it stopped: a finished run only gives
   * back its results, an interrupted one goes on, and one that never
   * started starts.
   */
  std::vector<ParameterChange>
  resumable_run(const Parameters  &study,
                const std::string &directory,
                const unsigned int n_steps);

  /**
   * One flowing run of an experiment that runs several (shear, flowing
   * layouts), each derived from the experiment's parameters
   * (RunParameters::derive()) into its own Output directory: the
   * IFEMSimulation of @p run's parameters in @p domain with @p observer,
   * set up (InputError before anything is written), then its
   * parameters.prm, the run (its tables and fields) and its own timing.csv.
   * Its timer summary goes to @p pcout; @p options are the study's.
   */
  void
  run_derived_flow(const RunParameters &run,
                   const FlowDomain    &domain,
                   RunObserver         &observer,
                   const MPI_Comm       communicator,
                   ConditionalOStream  &pcout,
                   const RunOptions    &options);
} // namespace rbc_ifem

#endif

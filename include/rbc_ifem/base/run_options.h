#ifndef rbc_ifem_base_run_options_h
#define rbc_ifem_base_run_options_h

namespace rbc_ifem
{
  /**
   * What the command line adds to the parameters: what a run may do to what
   * it finds, and whether it goes on where the size estimate says no.
   */
  struct RunOptions
  {
    /**
     * --overwrite: start over in an Output directory that holds the
     * checkpoints of an earlier run (in it or one folder down, as a study's
     * runs), removing those checkpoints first. Without it such a run is
     * refused, unless it resumes.
     */
    bool overwrite = false;
    /// --force: run although the size estimate (SizeEstimate) exceeds the
    /// memory the machine has.
    bool force = false;
  };
} // namespace rbc_ifem

#endif

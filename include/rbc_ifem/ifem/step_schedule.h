#ifndef rbc_ifem_ifem_step_schedule_h
#define rbc_ifem_ifem_step_schedule_h

#include <rbc_ifem/ifem/parameters.h>

namespace rbc_ifem
{
  /// What a step of a flowing run does after it has stepped.
  struct StepActions
  {
    bool diffusion  = false; ///< solve DM (Immersed cells/Diffusion interval)
    bool output     = false; ///< write fields and tables (Time/Output interval)
    bool progress   = false; ///< (Immersed cells/Progress interval)
    bool checkpoint = false; ///< (Immersed cells/Checkpoint interval)

    /// Whether the step does any of these: then it also records flow.csv
    /// and prints its progress line.
    bool
    any() const;
  };

  /**
   * When a flowing run does what besides stepping: every k steps for each
   * interval k > 0 of its parameters; the last step writes its output, and
   * a checkpoint if the run writes any.
   */
  class StepSchedule
  {
  public:
    StepSchedule(const TimeParameters     &time,
                 const ImmersedParameters &immersed);

    /// What step @p step (counted from 1) does.
    StepActions
    actions(const unsigned int step) const;

  private:
    const unsigned int n_steps;
    const unsigned int diffusion_interval, output_interval, progress_interval,
      checkpoint_interval;
  };

  // The functions, inline: they are a few comparisons each.
  namespace internal
  {
    /// Whether @p step is due every @p interval steps (0: never).
    inline bool
    due(const unsigned int step, const unsigned int interval)
    {
      return interval > 0 && step % interval == 0;
    }
  } // namespace internal

  inline bool
  StepActions::any() const
  {
    return diffusion || output || progress || checkpoint;
  }

  inline StepSchedule::StepSchedule(const TimeParameters     &time,
                                    const ImmersedParameters &immersed)
    : n_steps(time.n_steps)
    , diffusion_interval(immersed.diffusion_interval)
    , output_interval(time.output_interval)
    , progress_interval(immersed.progress_interval)
    , checkpoint_interval(immersed.checkpoint_interval)
  {}

  inline StepActions
  StepSchedule::actions(const unsigned int step) const
  {
    const bool  last = step == n_steps;
    StepActions actions;
    actions.diffusion  = internal::due(step, diffusion_interval);
    actions.output     = internal::due(step, output_interval) || last;
    actions.progress   = internal::due(step, progress_interval);
    actions.checkpoint = internal::due(step, checkpoint_interval) ||
                         (last && checkpoint_interval > 0);
    return actions;
  }
} // namespace rbc_ifem

#endif

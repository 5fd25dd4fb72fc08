#include <rbc_ifem/ifem/step_schedule.h>

namespace rbc_ifem
{
  namespace
  {
    bool
    due(const unsigned int step, const unsigned int interval)
    {
      return interval > 0 && step % interval == 0;
    }
  } // namespace

  bool
  StepActions::any() const
  {
    return diffusion || output || progress || checkpoint;
  }

  StepSchedule::StepSchedule(const TimeParameters     &time,
                             const ImmersedParameters &immersed)
    : n_steps(time.n_steps)
    , diffusion_interval(immersed.diffusion_interval)
    , output_interval(time.output_interval)
    , progress_interval(immersed.progress_interval)
    , checkpoint_interval(immersed.checkpoint_interval)
  {}

  StepActions
  StepSchedule::actions(const unsigned int step) const
  {
    const bool  last = step == n_steps;
    StepActions actions;
    actions.diffusion = due(step, diffusion_interval);
    actions.output    = due(step, output_interval) || last;
    actions.progress  = due(step, progress_interval);
    actions.checkpoint =
      due(step, checkpoint_interval) || (last && checkpoint_interval > 0);
    return actions;
  }
} // namespace rbc_ifem

#pragma once
// Timing honesty: a run whose time a table reports (a tradeoff table's compared runs, a matrix table of a
// time such as stats.wall_seconds) is timed after kTimedWarmUp untimed frames as the median of kTimedFrames
// unless the file says otherwise (`warm_up:`, `repeat:` per run): one frame's time varies by tens of
// percent from run to run. What is filled in goes to Experiment::defaults; a table that still rests on
// one frame (repeat: 1) gets a line in Experiment::warnings.
#include "libvri/experiment/experiment_spec.h"

namespace vri {

inline constexpr int kTimedWarmUp = 1;
inline constexpr int kTimedFrames = 3;

void applyTimingDefaults(Experiment& experiment);

}  // namespace vri

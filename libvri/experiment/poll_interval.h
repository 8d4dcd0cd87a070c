#pragma once
// How long vri-run waits between two looks at its Slurm jobs: --slurm-poll while something changes, then
// half as long again after each look that found every job as it was, up to kLongest (or --slurm-poll when
// that is longer), so that a long cluster run asks squeue a few times a minute, not once a second.
#include <algorithm>

namespace vri {

class PollInterval {
public:
    static constexpr double kLongest = 10.0;  // seconds: a finished job is seen within this

    explicit PollInterval(double shortest) : shortest_(shortest), current_(shortest) {}

    // The wait before the next look.
    double seconds() const { return current_; }
    // After a look: `changed` when some job's state differs from the look before.
    void looked(bool changed) {
        current_ = changed ? shortest_ : std::min(current_ * 1.5, std::max(kLongest, shortest_));
    }

private:
    double shortest_, current_;
};

}  // namespace vri

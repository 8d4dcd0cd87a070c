#pragma once
// What a wait on Slurm says while its jobs cannot start. squeue gives each pending job a reason: Dependency
// (it waits for another job of the run: nothing to say), or what the cluster lacks (Priority, Resources,
// PartitionDown, ReqNodeNotAvail, BeginTime, JobHeldUser, ...). Once none of the jobs waited for has run
// for a minute (or half of `maxSeconds`, if shorter) and some pend for such a reason, a line names how many
// pend and why; it comes again
// after twice as long each time, so that a long queue is neither silent nor noisy. Past `maxSeconds`
// (--slurm-max-pending; 0: never) the wait gives up with a vri::Error naming the jobs and their reasons.
#include <chrono>
#include <map>
#include <optional>
#include <ostream>
#include <string>

#include "libvri/experiment/slurm_commands.h"

namespace vri {

class PendingWatch {
public:
    using Clock = std::chrono::steady_clock;

    // `what`: how the line names the jobs ("small: Slurm jobs", "the Slurm check job").
    PendingWatch(std::string what, double maxSeconds);

    // After each squeue, with the states of the jobs waited for (a job that ended since the look before among
    // them, as the watch loops give them): writes the line to `out` when it is due; throws vri::Error past the limit.
    void update(const std::map<std::string, SlurmJob>& states, std::ostream& out, Clock::time_point now);

private:
    std::string what_;
    double maxSeconds_, firstSay_, nextSay_;
    std::optional<Clock::time_point> stuckSince_;  // since when no job ran and some pend for the cluster
};

}  // namespace vri

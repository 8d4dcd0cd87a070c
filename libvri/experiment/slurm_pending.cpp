#include "libvri/experiment/slurm_pending.h"

#include <algorithm>
#include <utility>

#include "libvri/experiment/step_costs.h"  // secondsText
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/printable.h"

namespace vri {

PendingWatch::PendingWatch(std::string what, double maxSeconds)
    : what_(std::move(what)), maxSeconds_(maxSeconds),
      firstSay_(maxSeconds > 0 ? std::min(60.0, maxSeconds / 2) : 60.0), nextSay_(firstSay_) {}

void PendingWatch::update(const std::map<std::string, SlurmJob>& states, std::ostream& out, Clock::time_point now) {
    std::map<std::string, int> reasons;  // pending for the cluster, by squeue's reason
    int pending = 0;
    bool ran = false;
    for (const auto& [id, job] : states) {
        if (job.state != "PENDING") {
            // Running, or ended since the last look (a short job can start and end between two): progress.
            ran = ran || job.state != "SUSPENDED";
            continue;
        }
        if (job.reason == "Dependency") continue;  // waits for a job of this run
        ++pending;
        // The reason is what the line is for: whole up to 200 bytes (a drained node's, "Nodes required for job are
        // DOWN, DRAINED or reserved for jobs in higher priority partitions", is 91; a limit's, naming the
        // association and its TRES, can be longer), the line itself then cut at kMaxMessageBytes.
        ++reasons[printableShort(job.reason.empty() ? "no reason given" : job.reason, 200)];
    }
    if (ran || pending == 0) {
        stuckSince_.reset();
        nextSay_ = firstSay_;
        return;
    }
    if (!stuckSince_) stuckSince_ = now;
    const double waited = std::chrono::duration<double>(now - *stuckSince_).count();
    std::string why;
    for (const auto& [reason, count] : reasons)
        why += (why.empty() ? "" : ", ") + reason + (count > 1 ? " x" + std::to_string(count) : "");
    const std::string line = what_ + ": " + std::to_string(pending) + (pending == 1 ? " job pending" : " jobs pending") +
                             " (squeue's reason: " + why + ") for " + secondsText(waited) +
                             ", none running";
    if (maxSeconds_ > 0 && waited >= maxSeconds_)
        throw Error(line + ": gave up after --slurm-max-pending " + exactNumber(maxSeconds_) + " s");
    if (waited >= nextSay_) {
        out << "vri-run: " << line << '\n';
        nextSay_ *= 2;
    }
}

}  // namespace vri

// What a wait on Slurm says while its jobs pend, and when it gives up (slurm_pending.h), on a clock the
// test sets: no sleeping, no timing.
#include <doctest/doctest.h>

#include <sstream>

#include "libvri/experiment/poll_interval.h"
#include "libvri/experiment/slurm_pending.h"
#include "libvri/util/error.h"

using namespace vri;

namespace {

std::map<std::string, SlurmJob> jobs(std::initializer_list<SlurmJob> list) {
    std::map<std::string, SlurmJob> m;
    for (const SlurmJob& j : list) m[j.id] = j;
    return m;
}

}  // namespace

TEST_CASE("PendingWatch: a line after the first interval, then at doubling ones; jobs waiting for others say nothing") {
    PendingWatch watch("Slurm jobs", 0);  // no limit: the first line after a minute
    const auto t0 = PendingWatch::Clock::now();
    const auto at = [&](double s) { return t0 + std::chrono::milliseconds(static_cast<long long>(s * 1000)); };
    std::ostringstream out;
    const auto stuck = jobs({{"1", "PENDING", "", "PartitionDown"}, {"2", "PENDING", "", "PartitionDown"},
                             {"3", "PENDING", "", "Dependency"}, {"4", "PENDING", "", "Priority"}});
    for (double s : {0.0, 30.0, 59.0}) watch.update(stuck, out, at(s));
    CHECK(out.str().empty());
    watch.update(stuck, out, at(61));
    CHECK(out.str() == "vri-run: Slurm jobs: 3 jobs pending (squeue's reason: PartitionDown x2, Priority) for 61.0 s, "
                       "none running\n");
    out.str("");
    watch.update(stuck, out, at(100));
    CHECK(out.str().empty());  // the next at 120 s
    watch.update(stuck, out, at(121));
    CHECK(out.str().find("for 2.0 min") != std::string::npos);
    // A job that runs resets the clock; so does nothing pending for the cluster.
    out.str("");
    watch.update(jobs({{"1", "RUNNING", "n1", "None"}, {"2", "PENDING", "", "Resources"}}), out, at(200));
    watch.update(jobs({{"2", "PENDING", "", "Resources"}}), out, at(230));
    CHECK(out.str().empty());
    watch.update(jobs({{"3", "PENDING", "", "Dependency"}}), out, at(400));
    CHECK(out.str().empty());
    // A short job that started and ended between two looks is progress too: its end resets the clock.
    watch.update(jobs({{"5", "PENDING", "", "Priority"}}), out, at(500));
    watch.update(jobs({{"4", "COMPLETED", "n1", "None"}, {"5", "PENDING", "", "Priority"}}), out, at(555));
    watch.update(jobs({{"5", "PENDING", "", "Priority"}}), out, at(590));
    CHECK(out.str().empty());  // 35 s since the job ended, not 90 since the first look
}

TEST_CASE("PendingWatch: --slurm-max-pending gives up with the jobs' reasons") {
    PendingWatch watch("the Slurm check job 7", 10);  // the first line halfway to the limit
    const auto t0 = PendingWatch::Clock::now();
    std::ostringstream out;
    const auto held = jobs({{"7", "PENDING", "", "JobHeldUser"}});
    watch.update(held, out, t0);
    watch.update(held, out, t0 + std::chrono::seconds(6));
    CHECK(out.str() == "vri-run: the Slurm check job 7: 1 job pending (squeue's reason: JobHeldUser) for 6.0 s, none running\n");
    CHECK_THROWS_WITH_AS(watch.update(held, out, t0 + std::chrono::seconds(10)),
                         "the Slurm check job 7: 1 job pending (squeue's reason: JobHeldUser) for 10.0 s, none running: "
                         "gave up after --slurm-max-pending 10 s",
                         Error);
}

TEST_CASE("the wait between two looks at the jobs grows while nothing changes and is short again on a change") {
    PollInterval interval(1.0);
    CHECK(interval.seconds() == 1.0);
    interval.looked(false);
    CHECK(interval.seconds() == 1.5);
    interval.looked(false);
    CHECK(interval.seconds() == 2.25);
    for (int i = 0; i < 20; ++i) interval.looked(false);
    CHECK(interval.seconds() == PollInterval::kLongest);
    interval.looked(true);
    CHECK(interval.seconds() == 1.0);
    PollInterval slow(60.0);  // a --slurm-poll above the longest is kept
    slow.looked(false);
    CHECK(slow.seconds() == 60.0);
}

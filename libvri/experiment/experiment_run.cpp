// vri-run's local executor: steps as child processes, up to --jobs at once (a step that times itself alone:
// Step::alone); and the choice of executor.
#include "libvri/experiment/experiment_run.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>

#include "libvri/experiment/slurm_executor.h"
#include "libvri/experiment/step_ledger.h"
#include "libvri/io/provenance.h"
#include "libvri/util/error.h"
#include "libvri/util/input_digest.h"
#include "libvri/util/load_average.h"
#include "libvri/util/process.h"

namespace vri {

namespace {

using Clock = std::chrono::steady_clock;

class LocalScheduler {
public:
    LocalScheduler(const Plan& plan, const RunOptions& options, FileHasher& hasher)
        : options_(options), ledger_(plan, options, hasher), host_(hostName()) {
        // The steps it starts inherit it: one plan runs at a time here.
        ::setenv(kInputDigestsVariable, std::filesystem::absolute(ledger_.digestRecord()).c_str(), 1);
    }

    std::vector<StepOutcome> run();

private:
    struct Child {
        std::size_t step;
        Clock::time_point start;
        std::optional<double> loadBefore;
        std::vector<std::string> beside;  // the steps that ran while it ran
    };

    bool startReady();  // starts or settles every step whose dependencies are settled; false when nothing changed
    void finish(pid_t pid, const ExitStatus& status);

    const RunOptions& options_;
    StepLedger ledger_;
    std::string host_;
    std::vector<bool> started_;
    std::vector<bool> mustRun_;  // ready, and needsRun said it must run
    std::map<pid_t, Child> running_;
};

bool LocalScheduler::startReady() {
    const Plan& plan = ledger_.plan();
    const auto aloneRunning = [&] {
        for (const auto& [pid, child] : running_)
            if (plan.steps[child.step].alone) return true;
        return false;
    };
    // Beside a step that runs alone nothing starts, and nothing is checked against the cache (which hashes
    // inputs and outputs): its time is its own.
    if (aloneRunning()) return false;
    bool changed = false;
    for (std::size_t i = 0; i < plan.steps.size() && !ledger_.hasFailure(); ++i) {
        if (started_[i] || static_cast<int>(running_.size()) >= options_.jobs) continue;
        bool ready = true;
        for (std::size_t d : plan.dependencies[i]) ready = ready && ledger_.settled(d);
        if (!ready) continue;
        if (!mustRun_[i]) {  // asked once a step, since needsRun settles a step that need not run
            if (!ledger_.needsRun(i)) {
                started_[i] = changed = true;
                continue;
            }
            mustRun_[i] = true;
        }
        // A step that runs alone waits for the machine to empty, and nothing after it in plan order starts
        // meanwhile, so that it is not starved.
        if (plan.steps[i].alone && !running_.empty()) break;
        started_[i] = changed = true;
        const std::vector<std::string> words = ledger_.prepare(i);
        ledger_.started(i);
        Child child{i, Clock::now(), loadAverage(), {}};
        for (auto& [pid, other] : running_) {
            other.beside.push_back(plan.steps[i].id);
            child.beside.push_back(plan.steps[other.step].id);
        }
        running_[startProcess(ledger_.program(i), words,
                              {.in = "/dev/null", .out = ledger_.logPath(i), .err = {}, .errToOut = true})] =
            std::move(child);
        if (plan.steps[i].alone) break;
    }
    return changed;
}

void LocalScheduler::finish(pid_t pid, const ExitStatus& status) {
    const auto found = running_.find(pid);
    if (found == running_.end()) return;
    const Child child = found->second;
    running_.erase(found);
    const double seconds = std::chrono::duration<double>(Clock::now() - child.start).count();
    if (status.ok())
        ledger_.succeeded(child.step, seconds,
                          {.executor = "local",
                           .node = host_,
                           .jobId = {},
                           .jobState = {},
                           .loadBefore = child.loadBefore,
                           .loadAfter = loadAverage(),
                           .beside = child.beside,
                           .earlierAttempts = {},
                           .peakRssMiB = peakRssMiB(status.peakRssKiB)});
    else
        ledger_.failed(child.step, "failed (" + status.describe() + ")", seconds);
}

std::vector<StepOutcome> LocalScheduler::run() {
    started_.assign(ledger_.size(), false);
    mustRun_.assign(ledger_.size(), false);
    for (;;) {
        while (startReady()) {
        }
        if (running_.empty()) break;
        const auto [pid, status] = waitAnyProcess();
        finish(pid, status);
    }
    return ledger_.result();
}

}  // namespace

std::vector<StepOutcome> runPlan(const Plan& plan, const RunOptions& options, FileHasher& hasher) {
    if (options.jobs < 1) throw Error("--jobs: expected at least 1, got " + std::to_string(options.jobs));
    if (options.executor == Executor::Slurm) return runPlanOnSlurm(plan, options, hasher);
    return LocalScheduler(plan, options, hasher).run();
}

}  // namespace vri

// The Slurm executor: submitting a plan's jobs, watching them, cancelling them.
#include "libvri/experiment/slurm_executor.h"

#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>
#include <set>

#include "libvri/experiment/slurm_commands.h"
#include "libvri/experiment/slurm_jobs.h"
#include "libvri/experiment/slurm_node.h"
#include "libvri/experiment/step_ledger.h"
#include "libvri/util/atomic_file.h"
#include "libvri/util/error.h"
#include "libvri/util/process.h"

namespace vri {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

// How long a file a finished job wrote may take to show here (a network file system's attribute cache),
// and how long squeue may fail in a row before vri-run gives up and cancels its jobs.
constexpr double kSharedFileDelaySeconds = 30;
constexpr double kSqueueOutageSeconds = 120;
// After scancel, how long vri-run waits for its jobs to end before it stops waiting.
constexpr double kCancelWaitSeconds = 60;
// The state of a job squeue has forgotten (it ended long ago: MinJobAge).
const std::string kForgotten = "ENDED";

volatile std::sig_atomic_t gInterrupt = 0;
extern "C" void onInterrupt(int signal) { gInterrupt = signal; }

// SIGINT, SIGTERM and SIGHUP set gInterrupt while it lives, so that vri-run cancels its jobs before it exits.
class InterruptGuard {
public:
    InterruptGuard() {
        gInterrupt = 0;
        struct sigaction action = {};
        action.sa_handler = onInterrupt;
        sigemptyset(&action.sa_mask);
        for (std::size_t k = 0; k < kSignals.size(); ++k) sigaction(kSignals[k], &action, &old_[k]);
    }
    ~InterruptGuard() {
        for (std::size_t k = 0; k < kSignals.size(); ++k) sigaction(kSignals[k], &old_[k], nullptr);
    }
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    static constexpr std::array<int, 3> kSignals{SIGINT, SIGTERM, SIGHUP};
    std::array<struct sigaction, 3> old_{};
};

// Sleeps, but returns early when a signal arrives (nanosleep's EINTR), so that an interrupt is seen at once.
void pause(double seconds) {
    timespec t{static_cast<time_t>(seconds), static_cast<long>((seconds - static_cast<time_t>(seconds)) * 1e9)};
    ::nanosleep(&t, nullptr);
}

std::string signalName(int signal) {
    switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    }
    return "signal " + std::to_string(signal);
}

// Job ids as a reader takes them in: runs of consecutive ids as "12-40", then how many ("12-40,45 (30 jobs)").
std::string jobList(const std::vector<std::string>& ids) {
    std::vector<long long> numbers;
    for (const std::string& id : ids) numbers.push_back(std::stoll(id));  // sbatch's ids: digits only
    std::sort(numbers.begin(), numbers.end());
    std::string text;
    for (std::size_t i = 0; i < numbers.size();) {
        std::size_t j = i;
        while (j + 1 < numbers.size() && numbers[j + 1] == numbers[j] + 1) ++j;
        if (!text.empty()) text += ',';
        text += std::to_string(numbers[i]);
        if (j > i) text.append(1, '-').append(std::to_string(numbers[j]));
        i = j + 1;
    }
    text.append(" (").append(std::to_string(ids.size())).append(ids.size() == 1 ? " job)" : " jobs)");
    return text;
}

// The job script: it runs its arguments as one command. The names and paths of a step reach the
// node as arguments of sbatch and of this script, never as text a shell reads.
void writeJobScript(const fs::path& script) {
    writeTextFile(script, "#!/bin/sh\n# vri-run's Slurm job: runs its arguments as one command.\nexec \"$@\"\n");
}

// Cancels `jobs` and waits until squeue shows them ended (or no longer knows them), at most kCancelWaitSeconds.
void cancelAndWait(const std::vector<std::string>& jobs, double pollSeconds) {
    cancelJobs(jobs);
    const auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < kCancelWaitSeconds) {
        std::map<std::string, SlurmJob> states;
        try {
            states = queryJobs(jobs);
        } catch (const Error&) {
            return;  // the controller does not answer: scancel has been asked, nothing more to do
        }
        bool running = false;
        for (const auto& [id, job] : states) running = running || !isFinalJobState(job.state);
        if (!running) return;
        pause(pollSeconds);
    }
}

class SlurmRun {
public:
    SlurmRun(const Plan& plan, const RunOptions& options, FileHasher& hasher)
        : plan_(plan), options_(options), ledger_(plan, options, hasher), slurmDir_(plan.resultsDir / ".steps" / "slurm") {}

    std::vector<StepOutcome> run();

private:
    struct Job {
        JobBundle bundle;
        std::string id;
        bool ended = false;
        std::set<std::size_t> dependsOn;  // indices of jobs
    };

    std::vector<std::size_t> stepsToRun();
    void submit(std::size_t j);
    void watch();
    void ended(std::size_t j, const SlurmJob& state);
    void abandonDependents(std::size_t j);
    std::vector<std::string> unendedIds() const;
    fs::path statusPath(std::size_t i) const {
        fs::path status = ledger_.logPath(i);
        return status.replace_extension(".status.json");
    }

    const Plan& plan_;
    const RunOptions& options_;
    StepLedger ledger_;
    fs::path slurmDir_;
    std::vector<Job> jobs_;
    std::map<std::size_t, std::size_t> jobOfStep_;
};

std::vector<std::size_t> SlurmRun::stepsToRun() {
    std::vector<std::size_t> run;
    std::vector<bool> willRun(plan_.steps.size(), false);
    for (std::size_t i = 0; i < plan_.steps.size(); ++i) {
        bool upstreamRuns = false;
        for (std::size_t d : plan_.dependencies[i]) upstreamRuns = upstreamRuns || willRun[d];
        if (upstreamRuns) {
            // Its inputs will be rewritten: nothing to compare a record with yet, so it runs. A step
            // whose own tool is not built is still settled (with its dependents) as locally.
            if (!fs::is_regular_file(ledger_.program(i))) {
                ledger_.needsRun(i);
                continue;
            }
        } else if (!ledger_.needsRun(i)) {
            continue;
        }
        willRun[i] = true;
        run.push_back(i);
    }
    return run;
}

void SlurmRun::submit(std::size_t j) {
    Job& job = jobs_[j];
    NodeSteps steps{fs::current_path(), {}};
    for (std::size_t i : job.bundle.steps) {
        const std::vector<std::string> words = ledger_.prepare(i);
        fs::remove(statusPath(i));
        steps.steps.push_back({plan_.steps[i].id, fs::absolute(ledger_.program(i)), words, fs::absolute(ledger_.logPath(i)),
                               fs::absolute(statusPath(i))});
        for (std::size_t d : plan_.dependencies[i])
            if (const auto found = jobOfStep_.find(d); found != jobOfStep_.end() && found->second != j)
                job.dependsOn.insert(found->second);
    }
    const std::string stem = "job-" + std::to_string(j);
    writeNodeSteps(slurmDir_ / (stem + ".json"), steps);

    const JobResources resources = jobResources(plan_, job.bundle, options_.slurm.cpus);
    std::vector<std::string> arguments{"--job-name=" + jobName(plan_, job.bundle),
                                       "--chdir=" + slurmDir_.string(),
                                       "--output=" + stem + ".out",  // relative to --chdir: no '%' of a path is read as a pattern
                                       "--cpus-per-task=" + std::to_string(resources.cpus),
                                       "--mem=" + std::to_string(resources.memoryMiB) + "M"};
    if (resources.minutes) arguments.push_back("--time=" + std::to_string(*resources.minutes));
    if (!job.dependsOn.empty()) {
        std::string after = "--dependency=afterok";
        for (std::size_t d : job.dependsOn) after += ":" + jobs_[d].id;
        arguments.insert(arguments.end(), {after, "--kill-on-invalid-dep=yes"});
    }
    arguments.insert(arguments.end(), options_.slurm.sbatchArguments.begin(), options_.slurm.sbatchArguments.end());
    arguments.insert(arguments.end(), {(slurmDir_ / "vri-job.sh").string(), fs::absolute(options_.toolDir / "vri-run").string(),
                                       "--slurm-node-steps", (slurmDir_ / (stem + ".json")).string()});
    job.id = submitJob(arguments);
}

std::vector<std::string> SlurmRun::unendedIds() const {
    std::vector<std::string> ids;
    for (const Job& job : jobs_)
        if (!job.ended && !job.id.empty()) ids.push_back(job.id);
    return ids;
}

void SlurmRun::abandonDependents(std::size_t failed) {
    // Jobs depend only on jobs before them: one pass finds everything downstream of `failed`.
    std::vector<bool> downstream(jobs_.size(), false);
    downstream[failed] = true;
    std::vector<std::string> cancel;
    for (std::size_t j = failed + 1; j < jobs_.size(); ++j) {
        Job& job = jobs_[j];
        for (std::size_t d : job.dependsOn) downstream[j] = downstream[j] || downstream[d];
        if (!downstream[j] || job.ended) continue;
        // Slurm cancels it too (--kill-on-invalid-dep); saying so here does not depend on that.
        cancel.push_back(job.id);
        job.ended = true;
        for (std::size_t i : job.bundle.steps)
            if (!ledger_.settled(i)) ledger_.abandoned(i, "a step it depends on failed (Slurm job " + jobs_[failed].id + ")");
    }
    cancelJobs(cancel);
}

void SlurmRun::ended(std::size_t j, const SlurmJob& state) {
    Job& job = jobs_[j];
    job.ended = true;
    // A job that completed wrote every status file, and so may have one squeue no longer knows.
    const bool completed = state.state == "COMPLETED" || state.state == kForgotten;
    const auto start = Clock::now();
    bool failed = false;
    for (std::size_t i : job.bundle.steps) {
        if (ledger_.settled(i)) continue;
        std::optional<NodeStepStatus> status = readNodeStepStatus(statusPath(i));
        // A shared file system may show a file late.
        while (!status && completed &&
               std::chrono::duration<double>(Clock::now() - start).count() < kSharedFileDelaySeconds) {
            pause(0.2);
            status = readNodeStepStatus(statusPath(i));
        }
        const std::string where = "Slurm job " + job.id + " " + state.state + (state.node.empty() ? "" : " on " + state.node);
        if (failed) {
            ledger_.abandoned(i, "an earlier step of its " + where + " failed");
        } else if (status && status->exited && status->code == 0) {
            ledger_.succeeded(i, status->wallSeconds,
                              {.executor = "slurm", .node = status->node, .jobId = job.id, .jobState = state.state});
        } else if (status) {
            const ExitStatus exit{status->exited, status->code, status->signal};
            ledger_.failed(i, "failed (" + exit.describe() + ") in " + where, status->wallSeconds);
            failed = true;
        } else if (state.reason == "DependencyNeverSatisfied") {
            ledger_.abandoned(i, "a step it depends on failed (" + where + ")");
            failed = true;
        } else {
            ledger_.failed(i, "failed: " + where + (state.reason.empty() || state.reason == "None" ? "" : " (" + state.reason + ")") +
                                  "; the job's output: " + (slurmDir_ / ("job-" + std::to_string(j) + ".out")).string(),
                           0);
            failed = true;
        }
    }
    if (failed) abandonDependents(j);
}

void SlurmRun::watch() {
    auto lastAnswer = Clock::now();
    for (std::vector<std::string> ids = unendedIds(); !ids.empty(); ids = unendedIds()) {
        if (gInterrupt) {
            cancelAndWait(ids, options_.slurm.pollSeconds);
            throw Error("interrupted by " + signalName(gInterrupt) + ": cancelled Slurm jobs " + jobList(ids));
        }
        pause(options_.slurm.pollSeconds);
        std::map<std::string, SlurmJob> states;
        try {
            states = queryJobs(ids);
            lastAnswer = Clock::now();
        } catch (const Error& e) {
            if (std::chrono::duration<double>(Clock::now() - lastAnswer).count() < kSqueueOutageSeconds) continue;
            cancelJobs(ids);
            throw Error(std::string(e.what()) + " for " + std::to_string(int(kSqueueOutageSeconds)) +
                        " s; cancelled Slurm jobs " + jobList(ids));
        }
        for (std::size_t j = 0; j < jobs_.size(); ++j) {
            if (jobs_[j].ended) continue;
            const auto found = states.find(jobs_[j].id);
            // A job squeue has forgotten ended long enough ago; its status files say how.
            if (found == states.end())
                ended(j, {jobs_[j].id, kForgotten, 0, "", "no longer known to squeue"});
            else if (isFinalJobState(found->second.state))
                ended(j, found->second);
        }
    }
}

std::vector<StepOutcome> SlurmRun::run() {
    const std::vector<std::size_t> steps = stepsToRun();
    if (steps.empty()) return ledger_.result();
    fs::remove_all(slurmDir_);  // the job files of an earlier run
    fs::create_directories(slurmDir_);
    writeJobScript(slurmDir_ / "vri-job.sh");
    for (JobBundle& bundle : bundleSteps(plan_, steps, options_.prices, options_.slurm.bundleSeconds)) {
        for (std::size_t i : bundle.steps) jobOfStep_[i] = jobs_.size();
        jobs_.push_back({std::move(bundle), "", false, {}});
    }
    const InterruptGuard guard;
    try {
        for (std::size_t j = 0; j < jobs_.size(); ++j) {
            if (gInterrupt) throw Error("interrupted by " + signalName(gInterrupt) + " while submitting");
            submit(j);
        }
    } catch (const Error& e) {
        const std::vector<std::string> submitted = unendedIds();
        cancelAndWait(submitted, options_.slurm.pollSeconds);
        throw Error(std::string(e.what()) +
                    (submitted.empty() ? "" : "; cancelled the Slurm jobs submitted before: " + jobList(submitted)));
    }
    std::vector<std::string> ids;
    for (const Job& job : jobs_) ids.push_back(job.id);
    std::cerr << "vri-run: " << plan_.resultsDir.filename().string() << ": " << steps.size() << " steps in Slurm jobs "
              << jobList(ids) << "\n";
    watch();
    return ledger_.result();
}

std::string randomToken() {
    std::random_device device;
    char text[33];
    std::snprintf(text, sizeof text, "%08x%08x%08x%08x", device(), device(), device(), device());
    return text;
}

}  // namespace

std::vector<StepOutcome> runPlanOnSlurm(const Plan& plan, const RunOptions& options, FileHasher& hasher) {
    return SlurmRun(plan, options, hasher).run();
}

void checkSlurmNodes(const std::vector<Plan>& plans, const fs::path& resultsRoot, const RunOptions& options,
                     FileHasher& hasher) {
    const fs::path folder = fs::absolute(resultsRoot) / ".slurm-check";
    const std::string token = randomToken();
    NodeCheck check{token, {}, {}, folder / (token + ".report.json")};
    std::set<fs::path> tools{fs::absolute(options.toolDir / "vri-run")}, files;
    for (const Plan& plan : plans)
        for (const Step& step : plan.steps) {
            if (fs::is_regular_file(options.toolDir / step.tool)) tools.insert(fs::absolute(options.toolDir / step.tool));
            for (const fs::path& input : step.inputs)
                if (fs::is_regular_file(input)) files.insert(fs::absolute(input));
        }
    for (const fs::path& tool : tools) check.tools.emplace_back(tool, hasher.digest(tool));
    for (const fs::path& file : files) check.files.emplace_back(file, fs::file_size(file));
    fs::create_directories(folder);
    const fs::path checkFile = folder / (token + ".json");
    writeNodeCheck(checkFile, check);
    writeJobScript(folder / "vri-job.sh");
    std::vector<std::string> arguments{"--job-name=vri:check", "--chdir=" + folder.string(), "--output=" + token + ".out",
                                       "--cpus-per-task=1", "--mem=256M", "--time=5"};
    arguments.insert(arguments.end(), options.slurm.sbatchArguments.begin(), options.slurm.sbatchArguments.end());
    arguments.insert(arguments.end(), {(folder / "vri-job.sh").string(), fs::absolute(options.toolDir / "vri-run").string(),
                                       "--slurm-node-check", checkFile.string()});
    const InterruptGuard guard;
    const std::string id = submitJob(arguments);
    for (;;) {
        if (gInterrupt) {
            cancelAndWait({id}, options.slurm.pollSeconds);
            throw Error("interrupted by " + signalName(gInterrupt) + ": cancelled the Slurm check job " + id);
        }
        pause(options.slurm.pollSeconds);
        const std::map<std::string, SlurmJob> states = queryJobs({id});
        const auto found = states.find(id);
        if (found == states.end() || isFinalJobState(found->second.state)) break;
    }
    std::vector<std::string> problems;
    try {
        problems = readNodeCheckReport(check);
    } catch (const Error&) {
        fs::remove_all(folder);
        throw;
    }
    fs::remove_all(folder);
    if (!problems.empty())
        throw Error(problems.front() + " (the Slurm check job " + id +
                    "): tools, inputs and the results folder must be shared with the compute nodes at the same paths");
}

}  // namespace vri

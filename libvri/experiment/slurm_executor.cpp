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

std::string randomToken() {
    std::random_device device;
    char text[33];
    std::snprintf(text, sizeof text, "%08x%08x%08x%08x", device(), device(), device(), device());
    return text;
}

// The check of slurm_executor.h, before the first job of a run: one small job on a compute node.
void checkSlurmNodes(const Plan& plan, const RunOptions& options, FileHasher& hasher) {
    const fs::path folder = fs::absolute(plan.resultsDir.parent_path()) / ".slurm-check";
    const std::string token = randomToken();
    NodeCheck check{token, {}, {}, folder / (token + ".report.json")};
    std::set<fs::path> tools, files;
    for (const fs::directory_entry& entry : fs::directory_iterator(options.toolDir))
        if (entry.is_regular_file() && entry.path().filename().string().starts_with("vri-"))
            tools.insert(fs::absolute(entry.path()));
    for (const Step& step : plan.steps)
        for (const fs::path& input : step.inputs)
            if (fs::is_regular_file(input)) files.insert(fs::absolute(input));
    for (const fs::path& tool : tools) check.tools.emplace_back(tool, hasher.digest(tool));
    for (const fs::path& file : files) check.files.emplace_back(file, fs::file_size(file));
    fs::create_directories(folder);
    const fs::path checkFile = folder / (token + ".json"), script = folder / (token + ".sh"), out = folder / (token + ".out");
    writeNodeCheck(checkFile, check);
    writeJobScript(script);
    // Only this check's files go, and its job's output stays when the check fails: the evidence.
    const auto removeOwnFiles = [&](bool keepOutput) {
        for (const fs::path& f : {checkFile, script, check.report}) fs::remove(f);
        if (!keepOutput) fs::remove(out);
        std::error_code ec;
        fs::remove(folder, ec);  // only when empty: another run's check may be there
    };
    std::vector<std::string> arguments{"--job-name=vri:check", "--chdir=" + folder.string(), "--output=" + out.filename().string(),
                                       "--cpus-per-task=1", "--mem=256M", "--time=10"};
    arguments.insert(arguments.end(), options.slurm.sbatchArguments.begin(), options.slurm.sbatchArguments.end());
    arguments.insert(arguments.end(), {script.string(), fs::absolute(options.toolDir / "vri-run").string(),
                                       "--slurm-node-check", checkFile.string()});
    std::vector<std::string> problems;
    bool completed = true;  // unless squeue says otherwise (one that forgot it cannot)
    try {
        const std::string id = submitJob(arguments);
        try {
            for (;;) {
                if (gInterrupt) throw Error("interrupted by " + signalName(gInterrupt) + ": cancelled the Slurm check job " + id);
                pause(options.slurm.pollSeconds);
                const std::map<std::string, SlurmJob> states = queryJobs({id});
                const auto found = states.find(id);
                if (found == states.end()) break;
                if (isFinalJobState(found->second.state)) {
                    completed = found->second.state == "COMPLETED";
                    break;
                }
            }
        } catch (...) {
            cancelAndWait({id}, options.slurm.pollSeconds);
            throw;
        }
        // A check that completed wrote its report, which a shared file system may show late.
        const auto start = Clock::now();
        while (completed && !fs::exists(check.report) && !gInterrupt &&
               std::chrono::duration<double>(Clock::now() - start).count() < kSharedFileDelaySeconds)
            pause(0.2);
        problems = readNodeCheckReport(check);
        if (!problems.empty())
            throw Error(problems.front() + " (the Slurm check job " + id +
                        "): tools, inputs and the results folder must be shared with the compute nodes at the same paths");
    } catch (...) {
        removeOwnFiles(true);
        throw;
    }
    removeOwnFiles(false);
}

class SlurmRun {
public:
    SlurmRun(const Plan& plan, const RunOptions& options, FileHasher& hasher)
        : plan_(plan), options_(options), hasher_(hasher), ledger_(plan, options, hasher),
          slurmDir_(plan.resultsDir / ".steps" / "slurm") {}

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
    // A run's job files carry a token of their own: a job of an earlier run still alive (one scancel
    // could not stop in time) finds its own files gone, and never reads this run's.
    std::string jobStem(std::size_t j) const { return "job-" + token_ + "-" + std::to_string(j); }
    fs::path statusPath(std::size_t i) const {
        fs::path status = ledger_.logPath(i);
        return status.replace_extension(".status.json");
    }

    const Plan& plan_;
    const RunOptions& options_;
    FileHasher& hasher_;
    StepLedger ledger_;
    fs::path slurmDir_;
    std::string token_ = randomToken();
    std::vector<Job> jobs_;
    std::map<std::size_t, std::size_t> jobOfStep_;
};

std::vector<std::size_t> SlurmRun::stepsToRun() {
    std::vector<std::size_t> run;
    std::vector<bool> willRun(plan_.steps.size(), false);
    for (std::size_t i = 0; i < plan_.steps.size(); ++i) {
        bool upstreamRuns = false, upstreamUnavailable = false;
        for (std::size_t d : plan_.dependencies[i]) {
            upstreamRuns = upstreamRuns || willRun[d];
            upstreamUnavailable = upstreamUnavailable || (ledger_.settled(d) &&
                                                          ledger_.outcome(d).state == StepOutcome::State::Unavailable);
        }
        if (upstreamRuns && !upstreamUnavailable) {
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
    const std::string stem = jobStem(j);
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
    try {
        job.id = submitJob(arguments);
    } catch (const Error& e) {
        throw Error("step '" + plan_.steps[job.bundle.steps.front()].id + "': " + e.what());
    }
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
    // A job that completed or failed wrote a status file for every step it ran (one squeue no longer
    // knows ended long ago); a shared file system may show them late. A job killed (cancelled, timed
    // out, preempted, out of memory) left none for the step it killed: nothing to wait for.
    const bool wroteStatuses = state.state == "COMPLETED" || state.state == "FAILED" || state.state == kForgotten;
    const auto start = Clock::now();
    // This job's status file for step i: one another job wrote (an earlier run's) is not this run's.
    const auto statusOf = [&](std::size_t i) {
        std::optional<NodeStepStatus> status = readNodeStepStatus(statusPath(i));
        return status && status->jobId == job.id ? status : std::nullopt;
    };
    bool failed = false;
    for (std::size_t i : job.bundle.steps) {
        if (ledger_.settled(i)) continue;
        std::optional<NodeStepStatus> status = failed ? std::nullopt : statusOf(i);
        while (!failed && !status && wroteStatuses && !gInterrupt &&
               std::chrono::duration<double>(Clock::now() - start).count() < kSharedFileDelaySeconds) {
            pause(0.2);
            status = statusOf(i);
        }
        const std::string where = "Slurm job " + job.id + " " + state.state + (state.node.empty() ? "" : " on " + state.node);
        if (failed) {
            ledger_.abandoned(i, "an earlier step of its " + where + " failed");
        } else if (status && status->exited && status->code == 0) {
            failed = !ledger_.succeeded(i, status->wallSeconds,
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
                                  "; the job's output: " + (slurmDir_ / (jobStem(j) + ".out")).string(),
                           0);
            failed = true;
        }
    }
    if (failed) abandonDependents(j);
}

void SlurmRun::watch() {
    auto lastAnswer = Clock::now();
    for (std::vector<std::string> ids = unendedIds(); !ids.empty(); ids = unendedIds()) {
        // run() cancels the jobs on the way out, whatever stops the watch.
        if (gInterrupt) throw Error("interrupted by " + signalName(gInterrupt) + ": cancelled Slurm jobs " + jobList(ids));
        pause(options_.slurm.pollSeconds);
        std::map<std::string, SlurmJob> states;
        try {
            states = queryJobs(ids);
            lastAnswer = Clock::now();
        } catch (const Error& e) {
            if (std::chrono::duration<double>(Clock::now() - lastAnswer).count() < kSqueueOutageSeconds) continue;
            throw Error(std::string(e.what()) + " for " + std::to_string(int(kSqueueOutageSeconds)) +
                        " s; cancelled Slurm jobs " + jobList(ids));
        }
        for (std::size_t j = 0; j < jobs_.size(); ++j) {
            if (jobs_[j].ended) continue;
            const auto found = states.find(jobs_[j].id);
            // A job squeue has forgotten ended long enough ago; its status files say how.
            if (found == states.end())
                ended(j, {jobs_[j].id, kForgotten, "", "no longer known to squeue"});
            else if (isFinalJobState(found->second.state))
                ended(j, found->second);
        }
    }
}

std::vector<StepOutcome> SlurmRun::run() {
    const std::vector<std::size_t> steps = stepsToRun();
    if (steps.empty()) return ledger_.result();
    const InterruptGuard guard;
    if (!*options_.slurm.nodesChecked) {
        checkSlurmNodes(plan_, options_, hasher_);
        *options_.slurm.nodesChecked = true;
    }
    fs::remove_all(slurmDir_);  // the job files of an earlier run
    fs::create_directories(slurmDir_);
    writeJobScript(slurmDir_ / "vri-job.sh");
    for (JobBundle& bundle : bundleSteps(plan_, steps, options_.prices, options_.slurm.bundleSeconds)) {
        for (std::size_t i : bundle.steps) jobOfStep_[i] = jobs_.size();
        jobs_.push_back({std::move(bundle), "", false, {}});
    }
    try {
        for (std::size_t j = 0; j < jobs_.size(); ++j) {
            if (gInterrupt) throw Error("interrupted by " + signalName(gInterrupt) + " while submitting");
            submit(j);
        }
    } catch (const std::exception& e) {
        const std::vector<std::string> submitted = unendedIds();
        cancelAndWait(submitted, options_.slurm.pollSeconds);
        throw Error(std::string(e.what()) +
                    (submitted.empty() ? "" : "; cancelled the Slurm jobs submitted before: " + jobList(submitted)));
    }
    std::vector<std::string> ids;
    for (const Job& job : jobs_) ids.push_back(job.id);
    std::cerr << "vri-run: " << plan_.resultsDir.filename().string() << ": " << steps.size() << " steps in Slurm jobs "
              << jobList(ids) << "\n";
    try {
        watch();
    } catch (...) {
        // Whatever stops the watch (an interrupt, squeue failing for minutes, a record that cannot be
        // written), no job of this run is left behind.
        cancelAndWait(unendedIds(), options_.slurm.pollSeconds);
        throw;
    }
    return ledger_.result();
}

}  // namespace

std::vector<StepOutcome> runPlanOnSlurm(const Plan& plan, const RunOptions& options, FileHasher& hasher) {
    return SlurmRun(plan, options, hasher).run();
}

}  // namespace vri
